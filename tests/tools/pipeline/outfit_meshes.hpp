#pragma once

#include "core/common/types.hpp"
#include "core/mesh/primitives.hpp"

namespace gr::test {

/// A closed cylinder about the z axis, outward: open_cylinder(radius, z0, z1, rings,
/// segments) and two flat caps, each a fan of `segments` faces about its centre (bottom
/// cap, then top cap, after the side's faces).
inline TriangleMesh closed_cylinder(double radius, double z0, double z1, int rings, int segments) {
  TriangleMesh mesh = open_cylinder(radius, z0, z1, rings, segments);
  const auto side_vertices = static_cast<int>(mesh.vertices.rows());
  const auto side_faces = mesh.faces.rows();
  const int bottom = side_vertices, top = side_vertices + 1;
  mesh.vertices.conservativeResize(side_vertices + 2, 3);
  mesh.vertices.row(bottom) << 0.0, 0.0, z0;
  mesh.vertices.row(top) << 0.0, 0.0, z1;
  mesh.faces.conservativeResize(side_faces + 2 * segments, 3);
  const int top_ring = (rings - 1) * segments;
  for (int s = 0; s < segments; ++s) {
    const int next = (s + 1) % segments;
    mesh.faces.row(side_faces + s) << bottom, next, s;
    mesh.faces.row(side_faces + segments + s) << top, top_ring + s, top_ring + next;
  }
  return mesh;
}

/// `mesh` moved by `offset`.
inline TriangleMesh translated(TriangleMesh mesh, const Vector3d& offset) {
  mesh.vertices.rowwise() += offset.transpose();
  return mesh;
}

/// A flat square-celled panel in the plane x = `x`, over |y| <= half_width and
/// z0 <= z <= z1, its normal along −x.
inline TriangleMesh panel(double x, double half_width, double z0, double z1) {
  constexpr int kCells = 4;
  return quad_grid(kCells, kCells, false, [&](int i, int j) {
    return Vector3d(x, half_width * (1.0 - 2.0 * j / kCells), z0 + (z1 - z0) * i / kCells);
  });
}

}  // namespace gr::test
