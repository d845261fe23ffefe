#include "core/mesh/primitives.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

namespace gr {

namespace {

constexpr double kPi = 3.14159265358979323846;

}  // namespace

TriangleMesh uv_sphere(double radius, const Vector3d& center, int rings, int segments) {
  TriangleMesh mesh;
  mesh.vertices.resize(2 + (rings - 1) * segments, 3);
  mesh.vertices.row(0) = (center + Vector3d(0, 0, radius)).transpose();
  mesh.vertices.row(1) = (center - Vector3d(0, 0, radius)).transpose();
  for (int r = 1; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const double theta = kPi * r / rings, phi = 2 * kPi * s / segments;
      mesh.vertices.row(2 + (r - 1) * segments + s) =
          (center + radius * Vector3d(std::sin(theta) * std::cos(phi),
                                      std::sin(theta) * std::sin(phi), std::cos(theta)))
              .transpose();
    }
  auto ring = [&](int r, int s) { return 2 + (r - 1) * segments + (s % segments); };
  std::vector<Eigen::Vector3i> faces;
  for (int s = 0; s < segments; ++s) {
    faces.emplace_back(0, ring(1, s), ring(1, s + 1));
    faces.emplace_back(1, ring(rings - 1, s + 1), ring(rings - 1, s));
    for (int r = 1; r + 1 < rings; ++r) {
      faces.emplace_back(ring(r, s), ring(r + 1, s), ring(r + 1, s + 1));
      faces.emplace_back(ring(r, s), ring(r + 1, s + 1), ring(r, s + 1));
    }
  }
  mesh.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    mesh.faces.row(static_cast<Eigen::Index>(f)) = faces[f].transpose();
  return mesh;
}

TriangleMesh icosphere(int subdivisions, double radius, const Vector3d& center) {
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
      v.push_back((v[static_cast<std::size_t>(a)] + v[static_cast<std::size_t>(b)]).normalized());
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
    mesh.vertices.row(static_cast<Eigen::Index>(i)) = (center + radius * v[i]).transpose();
  mesh.faces.resize(static_cast<Eigen::Index>(f.size()), 3);
  for (std::size_t i = 0; i < f.size(); ++i)
    mesh.faces.row(static_cast<Eigen::Index>(i)) << f[i][0], f[i][1], f[i][2];
  return mesh;
}

TriangleMesh quad_grid(int rows, int columns, bool wrap_columns,
                       const std::function<Vector3d(int, int)>& point) {
  const int stored_columns = wrap_columns ? columns : columns + 1;
  TriangleMesh mesh;
  mesh.vertices.resize((rows + 1) * stored_columns, 3);
  for (int i = 0; i <= rows; ++i)
    for (int j = 0; j < stored_columns; ++j)
      mesh.vertices.row(i * stored_columns + j) = point(i, j).transpose();
  mesh.faces.resize(2 * rows * columns, 3);
  const auto id = [&](int i, int j) { return i * stored_columns + j % stored_columns; };
  int f = 0;
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < columns; ++j) {
      mesh.faces.row(f++) << id(i, j), id(i, j + 1), id(i + 1, j + 1);
      mesh.faces.row(f++) << id(i, j), id(i + 1, j + 1), id(i + 1, j);
    }
  return mesh;
}

TriangleMesh open_cylinder(double radius, double z0, double z1, int rings, int segments) {
  return quad_grid(rings - 1, segments, true, [&](int r, int s) {
    const double angle = 2.0 * kPi * s / segments;
    return Vector3d(radius * std::cos(angle), radius * std::sin(angle),
                    z0 + (z1 - z0) * r / (rings - 1));
  });
}

TriangleMesh box(const Vector3d& half) {
  TriangleMesh mesh;
  mesh.vertices.resize(8, 3);
  for (int c = 0; c < 8; ++c)
    mesh.vertices.row(c) << (c & 1 ? half.x() : -half.x()), (c & 2 ? half.y() : -half.y()),
        (c & 4 ? half.z() : -half.z());
  mesh.faces.resize(12, 3);
  mesh.faces << 0, 6, 2, 0, 4, 6,  // -x
      1, 7, 5, 1, 3, 7,            // +x
      0, 5, 4, 0, 1, 5,            // -y
      2, 7, 3, 2, 6, 7,            // +y
      0, 3, 1, 0, 2, 3,            // -z
      4, 7, 6, 4, 5, 7;            // +z
  return mesh;
}

}  // namespace gr
