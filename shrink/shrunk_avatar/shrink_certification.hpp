#pragma once

#include <optional>
#include <vector>

#include "core/common/types.hpp"
#include "shrink/shrunk_avatar/shrink_result.hpp"

namespace gr {

/// The exact certification of a shrunk avatar against the garment (both in the same frame):
/// no avatar face may intersect or touch a garment face (validate's exact CGAL predicates),
/// and no garment vertex may lie inside the shrunk avatar (a garment wholly inside the body
/// passes the surface test). Inside means a generalized winding number of the shrunk avatar
/// above 1/2 in magnitude; values near 1/2 are summed exactly rather than approximated.
/// Degenerate avatar faces are tested as the segments or points they are.
/// @return nothing when the shrunk avatar is free of the garment, else the first conflict.
std::optional<ShrinkConflict> find_shrink_conflict(const TriangleMesh& shrunk_avatar,
                                                   const TriangleMesh& garment);

/// The points (rows) inside the shrunk avatar, by the winding number test above, in order.
std::vector<int> garment_vertices_inside(const TriangleMesh& shrunk_avatar,
                                         const Eigen::Ref<const MatrixX3d>& points);

}  // namespace gr
