#pragma once

#include <vector>

#include "core/common/types.hpp"

namespace gr {

/// Faces of `mesh` whose corners are exactly collinear (zero area; this includes repeated
/// corners and corners at identical coordinates), decided with exact predicates.
/// @return face indices in increasing order.
std::vector<int> find_degenerate_faces(const TriangleMesh& mesh);

}  // namespace gr
