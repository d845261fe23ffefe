#include "core/mesh/pieces.hpp"

#include <algorithm>
#include <numeric>

namespace gr {

std::vector<int> vertex_pieces(const TriangleMesh& mesh) {
  std::vector<int> parent(static_cast<std::size_t>(mesh.vertices.rows()));
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](int v) {
    while (parent[static_cast<std::size_t>(v)] != v) {
      parent[static_cast<std::size_t>(v)] =
          parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(v)])];
      v = parent[static_cast<std::size_t>(v)];
    }
    return v;
  };
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    for (int k = 1; k < 3; ++k) {
      const int a = root(mesh.faces(f, 0)), b = root(mesh.faces(f, k));
      if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
    }
  std::vector<int> pieces(parent.size());
  for (std::size_t v = 0; v < parent.size(); ++v) pieces[v] = root(static_cast<int>(v));
  return pieces;
}

}  // namespace gr
