#pragma once

#include <string>
#include <vector>

#include "core/common/types.hpp"

namespace gr {

/// A bone whose joints move linearly from the source skeleton (t = 0) to the target
/// skeleton (t = 1): a(t) = source_a + t (target_a - source_a), b(t) likewise. Normalized
/// scene units.
struct MovingBone {
  Vector3d source_a, source_b, target_a, target_b;

  Vector3d a(double t) const { return source_a + t * (target_a - source_a); }
  Vector3d b(double t) const { return source_b + t * (target_b - source_b); }
};

/// A garment boundary loop (hem, cuff, collar) and the bone its vertices are measured along.
struct LoopBone {
  std::vector<int> vertices;  ///< garment vertex ids along the loop
  MovingBone bone;
  int bone_index = -1;  ///< row of the skeleton's bones, or -1 for the virtual skirt bone
};

/// The hip and knee joints of the two legs, found from the bone graph alone: the legs are
/// the two chains that hang from the one branching joint (three or more bones) from which
/// exactly two leaf chains leave, each at least two joints long; the joint next to the
/// branching joint is the hip, the one after it the knee. When several branching joints
/// qualify, the one whose two chains hold the most joints wins.
struct LegJoints {
  int hips[2];
  int knees[2];
};

/// @param bones #B×2 joint indices.
/// @throw InputError when no branching joint has exactly two leaf chains of two or more
///        joints (the skeleton has no recognisable legs), naming `skeleton_name`.
LegJoints find_leg_joints(const Eigen::Ref<const MatrixX2i>& bones, int joint_count,
                          const std::string& skeleton_name);

/// Chooses the bone for each boundary loop of the garment, at t = 0 (source skeleton and
/// initial garment, same frame). A loop's centre is the mean of its vertices and its normal
/// Newell's normal. A loop of a skirt (its first vertex marked in `skirt_vertices`) takes
/// the virtual bone from the midpoint of the hips to the midpoint of the knees (see
/// find_leg_joints), which runs down between the legs. Any other loop takes the bone
/// closest to its centre (segment distance) among those whose direction is within 60
/// degrees of its normal (either sign) and that it goes round: seen along the bone, the
/// loop turns at least half a turn about its line, and its centre lies along the bone
/// within half the bone's length past either end (a cuff round a forearm, a hem round the
/// hips; not an eyelet beside a foot). A loop with no such bone, or with a zero normal,
/// gets none and is left out.
/// @param garment #Vg×3; source_joints, target_joints #J×3 (normalized scene units).
/// @param skirt_vertices per garment vertex, 1 for a skirt's; empty: no skirt.
/// @throw InputError from find_leg_joints when a loop is a skirt's and no legs are found.
std::vector<LoopBone> assign_loop_bones(const Eigen::Ref<const MatrixX3d>& garment,
                                        const std::vector<std::vector<int>>& loops,
                                        const Eigen::Ref<const MatrixX3d>& source_joints,
                                        const Eigen::Ref<const MatrixX3d>& target_joints,
                                        const Eigen::Ref<const MatrixX2i>& bones,
                                        const std::vector<char>& skirt_vertices = {});

}  // namespace gr
