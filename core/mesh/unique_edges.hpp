#pragma once

#include "core/common/types.hpp"

namespace gr {

/// Unique undirected edges of a face list (#E×2, smaller index first), sorted by (first,
/// second). A face corner repeated within one face gives no edge for that side.
/// @param faces #F×3, 0-based, non-negative.
MatrixX2i unique_edges(const Eigen::Ref<const MatrixX3i>& faces);

}  // namespace gr
