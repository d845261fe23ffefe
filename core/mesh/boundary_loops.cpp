#include "core/mesh/boundary_loops.hpp"

#include <algorithm>
#include <map>
#include <utility>

namespace gr {

std::vector<std::vector<int>> boundary_loops(const Eigen::Ref<const MatrixX3i>& faces) {
  // Count undirected edges; keep each face's directed edge.
  std::map<std::pair<int, int>, int> count;
  for (int f = 0; f < faces.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int a = faces(f, c), b = faces(f, (c + 1) % 3);
      ++count[{std::min(a, b), std::max(a, b)}];
    }
  std::multimap<int, int> next;  // boundary edge a -> b in face orientation
  for (int f = 0; f < faces.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int a = faces(f, c), b = faces(f, (c + 1) % 3);
      if (count[{std::min(a, b), std::max(a, b)}] == 1) next.emplace(a, b);
    }

  std::vector<std::vector<int>> loops;
  while (!next.empty()) {
    std::vector<int> loop;
    const int start = next.begin()->first;
    int current = start;
    for (;;) {
      const auto it = next.find(current);
      if (it == next.end()) break;
      loop.push_back(current);
      current = it->second;
      next.erase(it);
      if (current == start) break;
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

std::vector<bool> faces_on_open_edges(const Eigen::Ref<const MatrixX3i>& faces) {
  std::map<std::pair<int, int>, int> face_count;
  const auto edge = [&](Eigen::Index f, int k) {
    const int a = faces(f, k), b = faces(f, (k + 1) % 3);
    return std::pair{std::min(a, b), std::max(a, b)};
  };
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) ++face_count[edge(f, k)];
  std::vector<bool> open(static_cast<std::size_t>(faces.rows()), false);
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (face_count[edge(f, k)] == 1) open[static_cast<std::size_t>(f)] = true;
  return open;
}

}  // namespace gr
