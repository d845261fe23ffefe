#pragma once

#include <vector>

#include "core/common/types.hpp"

namespace gr {

/// Distance from each point (#P×3) to the nearest point of a triangle mesh, through
/// CGAL's AABB tree (independent of the solver's distance code). Same units as the inputs.
/// Zero-area faces are skipped (they add no surface). Empty mesh: +inf for every point.
std::vector<double> distances_to_surface(const TriangleMesh& surface,
                                         const Eigen::Ref<const MatrixX3d>& points);

}  // namespace gr
