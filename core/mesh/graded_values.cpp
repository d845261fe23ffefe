#include "core/mesh/graded_values.hpp"

#include <functional>
#include <queue>
#include <utility>

namespace gr {

void grade_down(std::vector<double>& values, const Eigen::Ref<const MatrixX2i>& edges,
                const Eigen::Ref<const MatrixX3d>& positions, double length) {
  const auto n = static_cast<std::size_t>(positions.rows());
  std::vector<std::vector<std::pair<int, double>>> adjacent(n);
  for (Eigen::Index e = 0; e < edges.rows(); ++e) {
    const int a = edges(e, 0), b = edges(e, 1);
    const double rise = (positions.row(a) - positions.row(b)).norm() / length;
    adjacent[static_cast<std::size_t>(a)].emplace_back(b, rise);
    adjacent[static_cast<std::size_t>(b)].emplace_back(a, rise);
  }
  // Dijkstra from every vertex at once, its value as its starting distance.
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  for (std::size_t v = 0; v < n; ++v) queue.emplace(values[v], static_cast<int>(v));
  while (!queue.empty()) {
    const auto [value, v] = queue.top();
    queue.pop();
    if (value > values[static_cast<std::size_t>(v)]) continue;
    for (const auto& [u, rise] : adjacent[static_cast<std::size_t>(v)]) {
      const double through = value + rise;
      if (through < values[static_cast<std::size_t>(u)]) {
        values[static_cast<std::size_t>(u)] = through;
        queue.emplace(through, u);
      }
    }
  }
}

}  // namespace gr
