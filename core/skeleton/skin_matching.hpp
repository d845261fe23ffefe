#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/io/gltf_document.hpp"

namespace gr {

/// Source joint name -> target joint name; a target of "-" leaves the source joint out.
using JointMap = std::vector<std::pair<std::string, std::string>>;

/// Reads a joint mapping file: one `source_name target_name` pair per line, `#` comments.
/// @throw InputError naming file and line for a line without exactly two names or a
///        source name given twice.
JointMap read_joint_map(const std::string& path);

/// Source and target skeletons taken from two skins, joint for joint.
struct MatchedSkeletons {
  Skeleton source;                ///< the source skin's kept joints, in its order
  Skeleton target;                ///< the same joints in the target skin, same bones
  std::vector<int> target_joint;  ///< per kept joint, its index in the target skin
  /// Per target-skin joint, the kept joint its weight goes to: itself when kept, else its
  /// nearest kept ancestor, else kept joint 0.
  std::vector<int> kept_joint_of_target;
};

/// Matches the joints of two skins by name (through `map` first when it names a joint).
/// Every source joint must be found unless mapped to "-". Bones join each kept joint to
/// its nearest kept ancestor in the source.
/// @throw InputError naming `target_path` and listing the source joints the target lacks,
///        or when fewer than two joints or no bone remain.
MatchedSkeletons match_skin_skeletons(const SkinBinding& source, const SkinBinding& target,
                                      const JointMap& map, const std::string& target_path);

/// A skin over a skeleton read from OBJ (joints without names or orientation): joint `i`
/// is named `joint_<i>`, placed by a translation, and parented by a breadth-first walk of
/// the bones from the lowest-numbered joint of each connected piece.
/// @param weights #J×#P, or empty for a skin without weights.
/// @pre weights is empty or has skeleton.joints.rows() rows.
SkinBinding skin_of_skeleton(const Skeleton& skeleton, const Eigen::MatrixXd& weights);

/// The bone (segment) nearest `point`, and where along it its closest point lies (0 at
/// bones(b, 0), 1 at bones(b, 1)); the first of equally near bones.
/// @pre the skeleton has at least one bone.
std::pair<Eigen::Index, double> nearest_bone(const Skeleton& skeleton, const Vector3d& point);

/// The default binding of points to a skeleton: each point to its nearest bone (segment),
/// shared between the bone's two joints by where its closest point lies along the bone
/// (1 - s and s). A zero-length bone counts as its first joint.
/// @param points #P×3, in the skeleton's frame.
/// @return #J×#P weights, each column summing to 1.
/// @pre the skeleton has at least one bone.
Eigen::MatrixXd nearest_bone_weights(const Skeleton& skeleton,
                                     const Eigen::Ref<const MatrixX3d>& points);

}  // namespace gr
