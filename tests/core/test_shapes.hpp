#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "core/common/types.hpp"

namespace gr::test {

/// An n×n vertex grid on [0,1]² lifted onto z = bump · (x² - y²) (curved, open boundary).
inline TriangleMesh curved_grid(int n, double bump = 0.3) {
  TriangleMesh mesh;
  mesh.vertices.resize(n * n, 3);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = double(i) / (n - 1), y = double(j) / (n - 1);
      mesh.vertices.row(j * n + i) << x, y, bump * (x * x - y * y);
    }
  mesh.faces.resize(2 * (n - 1) * (n - 1), 3);
  int f = 0;
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const int a = j * n + i, b = a + 1, c = a + n, d = c + 1;
      mesh.faces.row(f++) << a, b, d;
      mesh.faces.row(f++) << a, d, c;
    }
  return mesh;
}

/// An open cylinder of radius r around the z axis from z0 to z1: `around` vertices per ring,
/// `rings` rings; two boundary loops.
inline TriangleMesh open_cylinder(int around, int rings, double r, double z0, double z1) {
  TriangleMesh mesh;
  mesh.vertices.resize(around * rings, 3);
  for (int j = 0; j < rings; ++j)
    for (int i = 0; i < around; ++i) {
      const double angle = 2.0 * M_PI * i / around;
      mesh.vertices.row(j * around + i) << r * std::cos(angle), r * std::sin(angle),
          z0 + (z1 - z0) * j / (rings - 1);
    }
  mesh.faces.resize(2 * around * (rings - 1), 3);
  int f = 0;
  for (int j = 0; j + 1 < rings; ++j)
    for (int i = 0; i < around; ++i) {
      const int a = j * around + i, b = j * around + (i + 1) % around;
      const int c = a + around, d = b + around;
      mesh.faces.row(f++) << a, b, d;
      mesh.faces.row(f++) << a, d, c;
    }
  return mesh;
}

/// An icosphere (outward-oriented, closed) of the given radius and centre.
inline TriangleMesh icosphere(int subdivisions, double radius = 1.0,
                              const Vector3d& centre = Vector3d::Zero()) {
  const double p = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vector3d> v = {{-1, p, 0}, {1, p, 0}, {-1, -p, 0}, {1, -p, 0},
                             {0, -1, p}, {0, 1, p}, {0, -1, -p}, {0, 1, -p},
                             {p, 0, -1}, {p, 0, 1}, {-p, 0, -1}, {-p, 0, 1}};
  std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                       {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                       {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                       {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (auto& x : v) x.normalize();
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<int, int>, int> midpoint;
    const auto mid = [&](int a, int b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      const auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      v.push_back((v[a] + v[b]).normalized());
      return midpoint[key] = static_cast<int>(v.size()) - 1;
    };
    std::vector<std::array<int, 3>> next;
    for (const auto& t : f) {
      const int ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
      next.push_back({t[0], ab, ca});
      next.push_back({t[1], bc, ab});
      next.push_back({t[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    f = std::move(next);
  }
  TriangleMesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(v.size()), 3);
  for (std::size_t i = 0; i < v.size(); ++i)
    mesh.vertices.row(static_cast<Eigen::Index>(i)) = (centre + radius * v[i]).transpose();
  mesh.faces.resize(static_cast<Eigen::Index>(f.size()), 3);
  for (std::size_t i = 0; i < f.size(); ++i)
    mesh.faces.row(static_cast<Eigen::Index>(i)) << f[i][0], f[i][1], f[i][2];
  return mesh;
}

}  // namespace gr::test
