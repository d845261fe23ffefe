#include "validate/checks/position_identity.hpp"

#include <algorithm>
#include <numeric>

namespace gr {

std::vector<int> position_identity(const MatrixX3d& vertices) {
  const int n = static_cast<int>(vertices.rows());
  std::vector<int> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  const auto less = [&](int a, int b) {
    for (int k = 0; k < 3; ++k)
      if (vertices(a, k) != vertices(b, k)) return vertices(a, k) < vertices(b, k);
    return a < b;
  };
  std::sort(order.begin(), order.end(), less);
  std::vector<int> identity(static_cast<std::size_t>(n));
  for (std::size_t i = 0; i < order.size();) {
    // Rows with equal coordinates are consecutive, smallest index first.
    std::size_t j = i + 1;
    while (j < order.size() && vertices.row(order[j]) == vertices.row(order[i])) ++j;
    for (std::size_t k = i; k < j; ++k) identity[static_cast<std::size_t>(order[k])] = order[i];
    i = j;
  }
  return identity;
}

}  // namespace gr
