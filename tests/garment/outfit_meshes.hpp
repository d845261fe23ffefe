#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/common/types.hpp"
#include "core/io/mesh_file.hpp"
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

/// A capsule-like body along z: a sphere stretched to `half_length`, of `radius` around.
inline TriangleMesh capsule_body(double radius, double half_length) {
  TriangleMesh body = icosphere(3, 1.0);
  body.vertices.col(0) *= radius;
  body.vertices.col(1) *= radius;
  body.vertices.col(2) *= half_length;
  return body;
}

/// Three sleeves nested around a capsule of radius 0.3, written beside it, and a fatter
/// target capsule: the sleeves (radii 0.32, 0.34, 0.36) must grow around it in their order.
struct NestedSleeves {
  std::filesystem::path dir;
  std::vector<std::string> sleeves;  ///< inner, middle, outer
  std::string source_body;
  std::string avatar;
};

/// Writes the nested sleeves into `dir` as OBJ files: inner.obj, middle.obj, outer.obj,
/// source_body.obj (radius 0.3) and avatar.obj (radius 0.31), both 2.4 long.
inline NestedSleeves write_nested_sleeves(const std::filesystem::path& dir) {
  NestedSleeves scene;
  scene.dir = dir;
  const char* names[] = {"inner", "middle", "outer"};
  const double radii[] = {0.32, 0.34, 0.36};
  for (int k = 0; k < 3; ++k) {
    const std::string path = (scene.dir / (std::string(names[k]) + ".obj")).string();
    write_obj(path, open_cylinder(radii[k], -0.5, 0.5, 12, 32));
    scene.sleeves.push_back(path);
  }
  scene.source_body = (scene.dir / "source_body.obj").string();
  write_obj(scene.source_body, capsule_body(0.3, 1.2));
  scene.avatar = (scene.dir / "avatar.obj").string();
  write_obj(scene.avatar, capsule_body(0.31, 1.2));
  return scene;
}

}  // namespace gr::test
