#pragma once

#include "core/common/types.hpp"
#include "core/mesh/primitives.hpp"

namespace gr::test {

/// An n×n vertex grid on [0,1]² lifted onto z = bump · (x² - y²) (curved, open boundary).
inline TriangleMesh curved_grid(int n, double bump = 0.3) {
  return quad_grid(n - 1, n - 1, false, [&](int j, int i) {
    const double x = double(i) / (n - 1), y = double(j) / (n - 1);
    return Vector3d(x, y, bump * (x * x - y * y));
  });
}

}  // namespace gr::test
