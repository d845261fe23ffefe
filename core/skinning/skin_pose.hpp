#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/common/types.hpp"
#include "core/io/gltf_animation.hpp"
#include "core/io/gltf_document.hpp"

namespace gr {

/// Which of a clip's translation channels a skin takes.
enum class ClipTranslations {
  /// Every one: the clip was made for this very rig (it comes from the skin's own file).
  kAll,
  /// Those of the skin's root joints only: a clip from another file of the same rig turns
  /// the joints and moves the whole body, while each bone keeps this skin's length.
  kRoots,
};

/// How a clip drives a skin: per joint, the channel of its translation, rotation and scale
/// (-1: the joint keeps its rest value), joints matched to channels by node name.
struct ClipBinding {
  std::vector<std::array<int, 3>> channels;  ///< per skin joint: translation, rotation, scale
  int driven_joints = 0;                     ///< joints with at least one channel
  /// Names of the clip's nodes with a transform channel that no joint of the skin has.
  std::vector<std::string> unmatched_nodes;
};

/// Matches the clip's translation, rotation and scale channels to the skin's joints by name.
ClipBinding bind_clip(const SkinBinding& skin, const AnimationClip& clip,
                      ClipTranslations translations);

/// A joint's transform relative to its parent node.
struct JointTransform {
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
};

/// A pose of a skin: per joint, its transform.
using SkeletonPose = std::vector<JointTransform>;

/// Every joint at its rest transform.
SkeletonPose rest_pose(const SkinBinding& skin);

/// The pose `clip` gives at `time`: each joint's rest transform, its parts replaced where
/// `binding` gives them a channel.
SkeletonPose clip_pose(const SkinBinding& skin, const AnimationClip& clip,
                       const ClipBinding& binding, double time);

/// The pose a share `s` of the way from `from` to `to`: translations and scales linear,
/// rotations by spherical interpolation.
/// @pre both poses have the same joint count.
SkeletonPose blend_poses(const SkeletonPose& from, const SkeletonPose& to, double s);

/// The world matrix of every joint in `pose`, composed from the root down (through each
/// joint's parent_offset).
std::vector<Eigen::Matrix4d> joint_worlds(const SkinBinding& skin, const SkeletonPose& pose);

/// joint_worlds of clip_pose.
std::vector<Eigen::Matrix4d> posed_joint_worlds(const SkinBinding& skin, const AnimationClip& clip,
                                                const ClipBinding& binding, double time);

/// How many times a clip is sampled at `fps` (frame_times(clip, fps).size()). @pre fps > 0.
double frame_count(const AnimationClip& clip, double fps);

/// The times at which a clip is sampled: from its start, every 1/fps seconds, up to its end.
/// @pre fps > 0.
std::vector<double> frame_times(const AnimationClip& clip, double fps);

/// A skinned mesh ready to be posed: per vertex, its position in the bind space of the skin,
/// so that linear blend skinning with the rest joint worlds gives the positions it was
/// read at.
struct SkinnedMesh {
  MatrixX3d bind_positions;  ///< #P×3
  /// Per vertex whether it has a positive weight; an unweighted vertex stays where it is.
  std::vector<bool> weighted;
};

/// Prepares `rest_positions` (#P×3, the skinned mesh as read: posed by the skin at rest)
/// for posing: each vertex taken back through its rest blend matrix
/// sum_j w_j world_j inverse_bind_j (weights normalized to sum 1).
/// @pre skin.weights is #J×#P with no negative entry.
/// @throw std::invalid_argument when a weighted vertex's rest blend matrix is singular.
SkinnedMesh prepare_skinned_mesh(const SkinBinding& skin,
                                 const Eigen::Ref<const MatrixX3d>& rest_positions);

/// Linear blend skinning of `mesh` (prepared with `skin`): each vertex through sum_j w_j world_j
/// inverse_bind_j with the given joint worlds (posed_joint_worlds), as engines play a skin;
/// `bind_offsets` (#P×3, optional) moves the bind positions first, as morph targets do.
MatrixX3d pose_skinned_mesh(const SkinBinding& skin, const SkinnedMesh& mesh,
                            const std::vector<Eigen::Matrix4d>& worlds,
                            const MatrixX3d* bind_offsets = nullptr);

/// Per vertex, the linear part of its blend matrix with the given joint worlds: what turns a
/// bind-space offset into a posed one (identity for an unweighted vertex).
std::vector<Eigen::Matrix3d> blend_linear_parts(const SkinBinding& skin, const SkinnedMesh& mesh,
                                                const std::vector<Eigen::Matrix4d>& worlds);

}  // namespace gr
