#pragma once

#include <vector>

#include "core/common/types.hpp"

namespace gr {

/// The boundary loops of a triangle mesh: cycles of vertex ids along edges that belong to
/// exactly one face, each loop in the orientation of its faces. An open boundary chain
/// (only at a non-manifold vertex) is returned as the vertices it visits.
/// @param faces #F×3, 0-based.
std::vector<std::vector<int>> boundary_loops(const Eigen::Ref<const MatrixX3i>& faces);

/// Per face, whether one of its edges is open (has no second face): along a boundary, such
/// as the cut of a body cut away under clothes.
std::vector<bool> faces_on_open_edges(const Eigen::Ref<const MatrixX3i>& faces);

}  // namespace gr
