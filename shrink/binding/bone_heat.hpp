#pragma once

#include <vector>

#include "core/common/types.hpp"
#include "shrink/binding/voxel_binding.hpp"

namespace gr {

/// Bone heat diffusion (Baran and Popović 2007): per joint j, solves (-L + H) w_j = H p_j on
/// the avatar's surface, L the cotangent Laplacian with lumped vertex areas, H_ii =
/// strength / d_i^2 for d_i vertex i's distance to its nearest visible segment (0 when it
/// sees none), p_ij the share of vertex i's nearest visible segments (ties split) owned by
/// joint j. Negative cotangents count as 0 and every mesh edge conducts at least a little
/// (weight 1e-3), so -L is positive semi-definite and each connected part is one block.
/// One CHOLMOD factorization, one solve per joint.
/// @param visible #V×#S distance from each vertex to each segment it sees, infinity for
///        those it does not (a vertex seeing none is heated through its part only).
/// @param min_distance d_i is at least this (a bone touching the surface stays finite); > 0.
/// @return #J×#V non-negative heat, columns not normalized; zero columns for the vertices of
///         connected parts where no vertex sees a segment (the system is singular there).
/// @throw std::invalid_argument when the shapes do not match or min_distance <= 0.
/// @throw std::runtime_error when CHOLMOD finds the system not positive definite.
Eigen::MatrixXd bone_heat(const TriangleMesh& avatar, const std::vector<BoneSegment>& segments,
                          const Eigen::MatrixXd& visible, int joint_count, double min_distance,
                          double strength = 1.0);

}  // namespace gr
