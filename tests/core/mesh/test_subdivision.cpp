#include <map>
#include <utility>

#include <catch2/catch.hpp>

#include "core/mesh/primitives.hpp"
#include "core/mesh/subdivision.hpp"
#include "core/mesh/unique_edges.hpp"

namespace gr {

namespace {

double signed_volume(const TriangleMesh& mesh) {
  double volume = 0.0;
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    const Vector3d a = mesh.vertices.row(mesh.faces(f, 0)).transpose();
    const Vector3d b = mesh.vertices.row(mesh.faces(f, 1)).transpose();
    const Vector3d c = mesh.vertices.row(mesh.faces(f, 2)).transpose();
    volume += a.dot(b.cross(c)) / 6.0;
  }
  return volume;
}

}  // namespace

TEST_CASE("midpoint subdivision: four faces each, the same surface, closed stays closed",
          "[mesh][subdivision]") {
  const TriangleMesh sphere = icosphere(1);
  const MidpointSubdivision once = subdivide_at_midpoints(sphere);
  const Eigen::Index edges = unique_edges(sphere.faces).rows();
  CHECK(once.mesh.faces.rows() == 4 * sphere.faces.rows());
  CHECK(once.mesh.vertices.rows() == sphere.vertices.rows() + edges);
  CHECK(once.parents.rows() == edges);
  CHECK(once.mesh.vertices.topRows(sphere.vertices.rows()) == sphere.vertices);
  for (Eigen::Index e = 0; e < once.parents.rows(); ++e) {
    const Vector3d expected =
        0.5 * (sphere.vertices.row(once.parents(e, 0)) + sphere.vertices.row(once.parents(e, 1)))
                  .transpose();
    CHECK((once.mesh.vertices.row(sphere.vertices.rows() + e).transpose() - expected).norm() ==
          0.0);
  }
  // The refined faces tile the input faces: the enclosed volume and orientation are kept.
  CHECK(signed_volume(once.mesh) == Approx(signed_volume(sphere)).epsilon(1e-12));
  CHECK(signed_volume(once.mesh) > 0.0);
  // Closed: every edge has exactly two faces, one in each direction.
  std::map<std::pair<int, int>, int> directed;
  for (Eigen::Index f = 0; f < once.mesh.faces.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      ++directed[{once.mesh.faces(f, k), once.mesh.faces(f, (k + 1) % 3)}];
  for (const auto& [edge, count] : directed) {
    CAPTURE(edge.first, edge.second);
    CHECK(count == 1);
    CHECK(directed.count({edge.second, edge.first}) == 1);
  }
  // Euler characteristic 2, twice over.
  const TriangleMesh twice = subdivide_at_midpoints(once.mesh).mesh;
  const Eigen::Index twice_edges = unique_edges(twice.faces).rows();
  CHECK(twice.vertices.rows() - twice_edges + twice.faces.rows() == 2);
}

}  // namespace gr
