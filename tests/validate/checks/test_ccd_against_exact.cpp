// The core's CCD checked by the validator's exact predicates: the certificate's arithmetic
// (CGAL) must find no crossing anywhere along a step the CCD allowed.
#include <cmath>
#include <random>

#include <catch2/catch.hpp>

#include "core/candidates/candidates.hpp"
#include "core/ccd/ccd.hpp"
#include "core/distance/edge_edge_distance.hpp"
#include "core/distance/point_triangle_distance.hpp"
#include "validate/checks/mesh_intersections.hpp"

using gr::MatrixX3d;
using gr::Vector3d;

namespace {

/// Two separate triangles around random centres in the unit cube.
gr::TriangleMesh random_pair_of_triangles(std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0), corner(-0.3, 0.3);
  gr::TriangleMesh mesh;
  mesh.vertices.resize(6, 3);
  for (int t = 0; t < 2; ++t) {
    const Vector3d centre(unit(rng), unit(rng), unit(rng));
    for (int k = 0; k < 3; ++k)
      mesh.vertices.row(3 * t + k) =
          (centre + Vector3d(corner(rng), corner(rng), corner(rng))).transpose();
  }
  mesh.faces.resize(2, 3);
  mesh.faces << 0, 1, 2, 3, 4, 5;
  return mesh;
}

gr::TriangleMesh single_face(const gr::TriangleMesh& mesh, int f) {
  gr::TriangleMesh out;
  out.vertices = mesh.vertices;
  out.faces = mesh.faces.row(f);
  return out;
}

/// Garment–avatar and garment–garment crossings at stacked positions V, decided exactly.
std::size_t exact_crossings(const gr::ContactMesh& mesh, const gr::TriangleMesh& garment,
                            const gr::TriangleMesh& avatar, const MatrixX3d& V) {
  gr::TriangleMesh g = garment, a = avatar;
  g.vertices = V.topRows(mesh.garment_vertex_count);
  a.vertices = V.bottomRows(mesh.avatar_vertex_count);
  return gr::find_intersecting_face_pairs(g, a, 0).count +
         gr::find_intersecting_face_pairs(single_face(g, 0), single_face(g, 1), 0).count;
}

double pair_distance(const gr::Candidates& c, std::size_t k, const MatrixX3d& V) {
  const auto row = [&](int i) -> Vector3d { return V.row(i).transpose(); };
  if (k < c.point_triangle.size()) {
    const auto& pt = c.point_triangle[k];
    return std::sqrt(gr::point_triangle_distance_sq(row(pt.point), row(pt.triangle[0]),
                                                    row(pt.triangle[1]), row(pt.triangle[2])));
  }
  const auto& ee = c.edge_edge[k - c.point_triangle.size()];
  return std::sqrt(gr::edge_edge_distance_sq(row(ee.edge_a[0]), row(ee.edge_a[1]),
                                             row(ee.edge_b[0]), row(ee.edge_b[1])));
}

}  // namespace

TEST_CASE("CCD steps are free of crossings under exact predicates", "[ccd][exact][property]") {
  std::mt19937 rng(20250607);
  std::normal_distribution<double> motion(0.0, 0.5);
  const gr::CcdOptions options;
  const int trials = 300, substeps = 100;
  int limited = 0;
  for (int trial = 0; trial < trials; ++trial) {
    const gr::TriangleMesh garment = random_pair_of_triangles(rng),
                           avatar = random_pair_of_triangles(rng);
    const gr::ContactMesh mesh = gr::ContactMesh::build(garment, avatar, true);
    MatrixX3d V0(12, 3);
    V0 << garment.vertices, avatar.vertices;
    if (exact_crossings(mesh, garment, avatar, V0) > 0) continue;  // start must be free
    MatrixX3d V1 = V0;
    for (Eigen::Index i = 0; i < V1.size(); ++i) V1.data()[i] += motion(rng);

    const gr::Candidates candidates = gr::find_swept_candidates(mesh, V0, V1, 0.0);
    const double alpha = gr::max_step(candidates, V0, V1, options);
    CAPTURE(trial, alpha);
    REQUIRE(alpha >= 0.0);
    REQUIRE(alpha <= 1.0);
    if (alpha < 1.0) ++limited;
    for (int k = 1; k <= substeps; ++k) {
      const double t = alpha * k / substeps;
      const MatrixX3d Vt = V0 + t * (V1 - V0);
      CAPTURE(t);
      REQUIRE(exact_crossings(mesh, garment, avatar, Vt) == 0);
    }
    const MatrixX3d V_end = V0 + alpha * (V1 - V0);
    for (std::size_t k = 0; k < candidates.size(); ++k) {
      const double d0 = pair_distance(candidates, k, V0);
      CAPTURE(k, d0);
      REQUIRE(pair_distance(candidates, k, V_end) >=
              options.min_separation_ratio * d0 * (1.0 - 1e-9));
    }
  }
  // The motions are large enough that many steps are actually limited by contact.
  CHECK(limited > trials / 4);
}
