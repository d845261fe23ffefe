#pragma once

#include <initializer_list>

#include "core/common/types.hpp"

namespace gr::test {

/// A mesh from explicit vertex rows and face rows.
inline TriangleMesh make_mesh(std::initializer_list<std::initializer_list<double>> vertices,
                              std::initializer_list<std::initializer_list<int>> faces) {
  TriangleMesh m;
  m.vertices.resize(static_cast<Eigen::Index>(vertices.size()), 3);
  m.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  Eigen::Index r = 0;
  for (const auto& row : vertices) {
    Eigen::Index c = 0;
    for (double x : row) m.vertices(r, c++) = x;
    ++r;
  }
  r = 0;
  for (const auto& row : faces) {
    Eigen::Index c = 0;
    for (int x : row) m.faces(r, c++) = x;
    ++r;
  }
  return m;
}

/// One triangle.
inline TriangleMesh triangle(const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  TriangleMesh m;
  m.vertices.resize(3, 3);
  m.vertices.row(0) = a.transpose();
  m.vertices.row(1) = b.transpose();
  m.vertices.row(2) = c.transpose();
  m.faces.resize(1, 3);
  m.faces << 0, 1, 2;
  return m;
}

/// Both meshes as one (faces of `second` after those of `first`).
inline TriangleMesh concatenate(const TriangleMesh& first, const TriangleMesh& second) {
  TriangleMesh m;
  m.vertices.resize(first.vertices.rows() + second.vertices.rows(), 3);
  m.vertices << first.vertices, second.vertices;
  m.faces.resize(first.faces.rows() + second.faces.rows(), 3);
  m.faces << first.faces, (second.faces.array() + static_cast<int>(first.vertices.rows())).matrix();
  return m;
}

/// A strip extruded along y (width 1) from a polyline in the xz-plane, two triangles per
/// polyline segment: a garment-like open surface to fold.
inline TriangleMesh extruded_strip(std::initializer_list<Vector2d> polyline) {
  TriangleMesh m;
  const int n = static_cast<int>(polyline.size());
  m.vertices.resize(2 * n, 3);
  int i = 0;
  for (const Vector2d& p : polyline) {
    m.vertices.row(2 * i) << p.x(), 0.0, p.y();
    m.vertices.row(2 * i + 1) << p.x(), 1.0, p.y();
    ++i;
  }
  m.faces.resize(2 * (n - 1), 3);
  for (int s = 0; s + 1 < n; ++s) {
    m.faces.row(2 * s) << 2 * s, 2 * s + 2, 2 * s + 1;
    m.faces.row(2 * s + 1) << 2 * s + 1, 2 * s + 2, 2 * s + 3;
  }
  return m;
}

}  // namespace gr::test
