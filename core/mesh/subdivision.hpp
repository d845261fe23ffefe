#pragma once

#include "core/common/types.hpp"

namespace gr {

/// A mesh refined by one midpoint subdivision, and where its new vertices came from.
struct MidpointSubdivision {
  /// Rows 0..#V-1 are the input's vertices; then one vertex per unique edge, at its
  /// midpoint, in unique_edges order. Every input face becomes four, in its orientation.
  TriangleMesh mesh;
  /// Row k: the two input vertices whose edge vertex #V + k halves (#E×2).
  MatrixX2i parents;
};

/// Splits every triangle into four at its edges' midpoints: corner triangles (a, ab, ca),
/// (ab, b, bc), (ca, bc, c), then the middle one (ab, bc, ca), so #F becomes 4 #F and #V
/// becomes #V + #E. Shared edges share their midpoint, so a manifold mesh stays
/// manifold and closed meshes stay closed.
/// @pre faces index vertices; a face with a repeated corner has no edge on that side and
///      keeps the repeated vertex there.
MidpointSubdivision subdivide_at_midpoints(const TriangleMesh& mesh);

}  // namespace gr
