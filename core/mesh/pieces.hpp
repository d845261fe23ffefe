#pragma once

#include <vector>

#include "core/common/types.hpp"

namespace gr {

/// Per vertex of `mesh`, its piece: the smallest vertex id among the vertices it is
/// connected to over face edges (a vertex in no face is a piece of its own).
std::vector<int> vertex_pieces(const TriangleMesh& mesh);

}  // namespace gr
