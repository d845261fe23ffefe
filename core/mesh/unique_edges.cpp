#include "core/mesh/unique_edges.hpp"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace gr {

MatrixX2i unique_edges(const Eigen::Ref<const MatrixX3i>& faces) {
  // One 64-bit key per directed-to-undirected edge, sorted and deduplicated.
  std::vector<std::uint64_t> keys;
  keys.reserve(static_cast<std::size_t>(faces.rows()) * 3);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const auto a = static_cast<std::uint32_t>(faces(f, k));
      const auto b = static_cast<std::uint32_t>(faces(f, (k + 1) % 3));
      if (a == b) continue;
      keys.push_back(std::uint64_t{std::min(a, b)} << 32 | std::max(a, b));
    }
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  MatrixX2i edges(static_cast<Eigen::Index>(keys.size()), 2);
  for (std::size_t e = 0; e < keys.size(); ++e) {
    edges(static_cast<Eigen::Index>(e), 0) = static_cast<int>(keys[e] >> 32);
    edges(static_cast<Eigen::Index>(e), 1) = static_cast<int>(keys[e] & 0xffffffffu);
  }
  return edges;
}

}  // namespace gr
