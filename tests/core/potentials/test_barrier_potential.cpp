#include <cmath>

#include <Eigen/Eigenvalues>
#include <catch2/catch.hpp>

#include "core/barrier/barrier.hpp"
#include "core/common/errors.hpp"
#include "core/distance/distance_test_support.hpp"
#include "core/distance/edge_edge_distance.hpp"
#include "core/distance/edge_edge_mollifier.hpp"
#include "core/distance/point_triangle_distance.hpp"
#include "core/potentials/barrier_potential.hpp"

using gr::MatrixX3d;
using gr::Vector3d;

namespace {

/// Rows: 0 a point, 1-3 a triangle, 4-5 edge a, 6-7 edge b.
MatrixX3d scene(const Vector3d& point, double edge_angle, double edge_height) {
  MatrixX3d V(8, 3);
  V.row(0) = point.transpose();
  V.row(1) << 0, 0, 0;
  V.row(2) << 1, 0, 0;
  V.row(3) << 0, 1, 0;
  V.row(4) << 2, 0, 0;
  V.row(5) << 3, 0, 0;
  V.row(6) << 2.2, 0.05, edge_height;
  V.row(7) = V.row(6) + 1.1 * Eigen::RowVector3d(std::cos(edge_angle), std::sin(edge_angle), 0.0);
  return V;
}

gr::Candidates pairs() {
  gr::Candidates c;
  c.point_triangle.push_back({0, {1, 2, 3}});
  c.edge_edge.push_back({{4, 5}, {6, 7}});
  return c;
}

MatrixX3d as_positions(const Eigen::VectorXd& x) {
  return Eigen::Map<const MatrixX3d>(x.data(), x.size() / 3, 3);
}

Eigen::VectorXd as_vector(const MatrixX3d& V) {
  return Eigen::Map<const Eigen::VectorXd>(V.data(), V.size());
}

}  // namespace

TEST_CASE("barrier potential derivatives match finite differences", "[potentials][barrier][grad]") {
  const double dhat = 0.5;
  const Vector3d point = GENERATE(Vector3d(0.3, 0.3, 0.2), Vector3d(0.5, -0.2, 0.1),
                                  Vector3d(-0.1, -0.2, 0.25), Vector3d(0.3, 0.3, 1e-3));
  // Crossing edges, edges inside the mollifier's band, and parallel edges.
  const double angle = GENERATE(1.2, 0.02, 1e-10, 0.0);
  const double height = GENERATE(0.3, 0.01);
  CAPTURE(point.transpose(), angle, height);
  const MatrixX3d V = scene(point, angle, height);
  const MatrixX3d rest = scene(point, 1.2, 0.3);
  const gr::BarrierPotential potential(dhat, rest);
  const gr::Candidates c = pairs();

  const auto value = [&](const Eigen::VectorXd& x) { return potential.value(c, as_positions(x)); };
  const auto gradient = [&](const Eigen::VectorXd& x) {
    return potential.gradient(c, as_positions(x));
  };
  const Eigen::VectorXd x = as_vector(V);
  const Eigen::VectorXd g = gradient(x);
  const Eigen::MatrixXd H = potential.hessian(c, V, false);
  // Step scaled to the smallest distance so the difference stays inside one region.
  const double h = 1e-7;
  CHECK(g.norm() > 0.0);
  CHECK(gr::test::fd_matches(g, gr::test::fd_gradient(value, x, h), 1e-5, 1e-12));
  CHECK(gr::test::fd_matches(H, gr::test::fd_hessian(gradient, x, h), 1e-5, 1e-12));

  // The value is the sum of the two pairs' barriers (edge–edge mollified).
  const double xhat = dhat * dhat;
  const auto row = [&](int i) -> Vector3d { return V.row(i).transpose(); };
  const double pt =
      gr::barrier(gr::point_triangle_distance_sq(row(0), row(1), row(2), row(3)), xhat);
  const double eps = 1e-3 * 1.0 * 1.21;
  const double ee = gr::mollifier((row(5) - row(4)).cross(row(7) - row(6)).squaredNorm(), eps) *
                    gr::barrier(gr::edge_edge_distance_sq(row(4), row(5), row(6), row(7)), xhat);
  CHECK(potential.value(c, V) == Approx(pt + ee).epsilon(1e-12));

  // Projection leaves no negative eigenvalue, and changes nothing that was PSD already.
  const Eigen::MatrixXd projected = potential.hessian(c, V, true);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(projected);
  CHECK(eigen.eigenvalues().minCoeff() >= -1e-12 * std::max(1.0, eigen.eigenvalues().maxCoeff()));
  // Translations stay free: the projection keeps them in the null space.
  const Eigen::VectorXd shift = Eigen::Vector3d(0.3, -0.2, 0.5).replicate(8, 1);
  CHECK((projected * shift).norm() <= 1e-9 * std::max(1.0, projected.norm()));
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> raw(H);
  if (raw.eigenvalues().minCoeff() >= 0.0) CHECK((projected - H).norm() <= 1e-12 * H.norm());
}

TEST_CASE("barrier potential outside dhat, at zero distance, and its minimum distance",
          "[potentials][barrier]") {
  const MatrixX3d V = scene(Vector3d(0.3, 0.3, 0.2), 1.2, 0.3);
  const gr::BarrierPotential potential(0.1, V);
  const gr::Candidates c = pairs();
  CHECK(potential.value(c, V) == 0.0);
  CHECK(potential.gradient(c, V).isZero());
  CHECK(potential.hessian(c, V).nonZeros() == 0);
  CHECK(potential.minimum_distance(c, V) == Approx(0.2));
  CHECK(std::isinf(potential.minimum_distance(gr::Candidates{}, V)));

  const MatrixX3d touching = scene(Vector3d(0.3, 0.3, 0.0), 1.2, 0.3);
  CHECK(std::isinf(potential.value(c, touching)));
  CHECK(potential.minimum_distance(c, touching) == 0.0);
  CHECK_THROWS_AS(gr::BarrierPotential(0.0, V), gr::InputError);
}
