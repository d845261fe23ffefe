#include "core/mesh/vertex_neighbours.hpp"

#include <algorithm>

namespace gr {

std::vector<std::vector<int>> vertex_neighbours(const TriangleMesh& mesh) {
  std::vector<std::vector<int>> neighbours(static_cast<std::size_t>(mesh.vertices.rows()));
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int a = mesh.faces(f, c), b = mesh.faces(f, (c + 1) % 3);
      neighbours[static_cast<std::size_t>(a)].push_back(b);
      neighbours[static_cast<std::size_t>(b)].push_back(a);
    }
  for (auto& list : neighbours) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return neighbours;
}

}  // namespace gr
