#pragma once

#include <string>
#include <vector>

#include "core/common/types.hpp"
#include "core/io/rig_files.hpp"

namespace gr {

/// How skinning blends the joints' motions at a vertex.
enum class SkinningMethod {
  kLinearBlend,     ///< the weighted sum of the joints' matrices (what engines play)
  kDualQuaternion,  ///< the normalized weighted sum of their dual quaternions: no collapse
};

const char* to_string(SkinningMethod method);
/// @throw std::invalid_argument for a name other than "linear-blend" or "dual-quaternion".
SkinningMethod parse_skinning_method(const std::string& name);

/// Per joint of `source`, the rigid motion that brings it into the pose of `target`: each
/// joint turned so that its bones to its children point as the target's do (the smallest
/// turn for one child, the best fit over several), bone lengths kept, the roots staying
/// where they are. A joint without children turns with its parent.
/// @pre the skeletons correspond joint for joint and bone for bone (check_skeletons_match).
std::vector<Eigen::Isometry3d> pose_transfer_motions(const Skeleton& source,
                                                     const Skeleton& target);

/// The source skeleton moved by its motions (pose_transfer_motions): the target's pose with
/// the source's bone lengths.
MatrixX3d moved_joints(const Skeleton& source, const std::vector<Eigen::Isometry3d>& motions);

/// `points` (#P×3) moved by the joints' motions blended with `weights` (#J×#P, columns
/// normalized here; a column summing to 0 keeps its point).
/// @pre weights has one row per motion.
MatrixX3d skin_by_motions(const Eigen::Ref<const MatrixX3d>& points, const Eigen::MatrixXd& weights,
                          const std::vector<Eigen::Isometry3d>& motions, SkinningMethod method);

}  // namespace gr
