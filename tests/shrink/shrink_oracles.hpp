#pragma once

#include <cmath>
#include <limits>

#include <catch2/catch.hpp>

#include "core/common/types.hpp"
#include "core/distance/point_triangle_distance.hpp"
#include "shrink/level_set/triangle_tree.hpp"
#include "shrink/shrunk_avatar/shrink_certification.hpp"
#include "shrink/shrunk_avatar/shrink_result.hpp"
#include "validate/checks/mesh_intersections.hpp"

namespace gr::test {

/// Oracle: the winding number summing every triangle's solid angle, from unit vectors
/// (tan(Ω/2) = â·(b̂×ĉ) / (1 + â·b̂ + b̂·ĉ + ĉ·â)), written apart from the library's.
inline double brute_force_winding_number(const TriangleMesh& mesh, const Vector3d& p) {
  double sum = 0.0;
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    const Vector3d a = (mesh.vertices.row(mesh.faces(f, 0)).transpose() - p).normalized();
    const Vector3d b = (mesh.vertices.row(mesh.faces(f, 1)).transpose() - p).normalized();
    const Vector3d c = (mesh.vertices.row(mesh.faces(f, 2)).transpose() - p).normalized();
    sum += 2.0 * std::atan2(a.dot(b.cross(c)), 1.0 + a.dot(b) + b.dot(c) + c.dot(a));
  }
  return sum / (4.0 * 3.14159265358979323846);
}

/// Oracle: point-to-mesh distance as the minimum over every triangle of the exact
/// point-triangle distance (itself checked against dense sampling).
inline double brute_force_distance(const TriangleMesh& mesh, const Vector3d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    best = std::min(best,
                    point_triangle_distance_sq(p, mesh.vertices.row(mesh.faces(f, 0)).transpose(),
                                               mesh.vertices.row(mesh.faces(f, 1)).transpose(),
                                               mesh.vertices.row(mesh.faces(f, 2)).transpose()));
  return std::sqrt(best);
}

/// True when some face has two corners at exactly the same position.
inline bool has_coincident_corners(const TriangleMesh& mesh) {
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      if (mesh.vertices.row(mesh.faces(f, c)) == mesh.vertices.row(mesh.faces(f, (c + 1) % 3)))
        return true;
  return false;
}

/// Requires `result` to be a shrunk avatar (avatar's faces) that crosses no garment face by
/// the validator's exact test and that the shrink's own check accepts.
inline void require_certified(const TriangleMesh& avatar, const ShrinkResult& result,
                              const TriangleMesh& garment) {
  const TriangleMesh shrunk{result.vertices, avatar.faces};
  REQUIRE(result.vertices.rows() == avatar.vertices.rows());
  REQUIRE(find_intersecting_face_pairs(shrunk, garment).count == 0);
  REQUIRE_FALSE(find_shrink_conflict(shrunk, garment).has_value());
}

}  // namespace gr::test
