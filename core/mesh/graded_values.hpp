#pragma once

#include <vector>

#include "core/common/types.hpp"

namespace gr {

/// Lowers per-vertex `values` so that along every edge they rise by at most the edge's
/// length over `length`: the largest function at most `values` with that slope, a value
/// lowered at one vertex fading in around it over `length`. Exact (shortest paths along
/// the edges from every vertex, in order of value).
/// @param edges #E×2 vertex index pairs into `positions`.
/// @pre length > 0, values has one entry per row of positions.
void grade_down(std::vector<double>& values, const Eigen::Ref<const MatrixX2i>& edges,
                const Eigen::Ref<const MatrixX3d>& positions, double length);

}  // namespace gr
