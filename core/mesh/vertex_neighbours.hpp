#pragma once

#include <vector>

#include "core/common/types.hpp"

namespace gr {

/// Per vertex of `mesh`, the vertices that share an edge with it, sorted, without repeats.
std::vector<std::vector<int>> vertex_neighbours(const TriangleMesh& mesh);

}  // namespace gr
