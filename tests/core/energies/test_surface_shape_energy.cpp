#include <catch2/catch.hpp>

#include <Eigen/Dense>

#include "core/energies/energy_checks.hpp"
#include "core/energies/surface_shape_energy.hpp"
#include "core/test_shapes.hpp"

using namespace gr;

namespace {

MatrixX3d rigidly_moved(const MatrixX3d& V, double angle, const Vector3d& axis,
                        const Vector3d& shift) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  MatrixX3d out = V;
  for (Eigen::Index i = 0; i < V.rows(); ++i)
    out.row(i) = (R * V.row(i).transpose() + shift).transpose();
  return out;
}

/// Two random triangles sharing an edge (one element), from a seeded generator.
TriangleMesh random_hinge(int seed) {
  std::srand(static_cast<unsigned>(seed));
  TriangleMesh rest;
  rest.vertices = MatrixX3d::Random(4, 3);
  rest.faces.resize(2, 3);
  rest.faces << 0, 1, 2, 1, 0, 3;
  return rest;
}

/// The element's four corners at rest (local coordinates q), each coordinate moved by a
/// uniform random amount in [-perturbation, perturbation].
SurfaceShapeEnergy::LocalVector perturbed_corners(const TriangleMesh& rest,
                                                  const SurfaceShapeEnergy::Element& element,
                                                  double perturbation) {
  SurfaceShapeEnergy::LocalVector q;
  for (int v = 0; v < 4; ++v)
    q.segment<3>(3 * v) = rest.vertices.row(element.vertices[v]).transpose();
  return q + perturbation * SurfaceShapeEnergy::LocalVector::Random();
}

}  // namespace

TEST_CASE("surface shape energy: element gradient and Hessian match finite differences",
          "[energies][surface][grad][hess]") {
  const int seed = GENERATE(1, 2, 3, 4);
  CAPTURE(seed);
  const TriangleMesh rest = random_hinge(seed);
  const SurfaceShapeEnergy energy(rest, DofLayout{4});
  REQUIRE(energy.elements().size() == 1);
  const auto& element = energy.elements()[0];

  using Local = SurfaceShapeEnergy::LocalVector;
  const Local q = perturbed_corners(rest, element, 0.3);

  const auto f = [&](const Eigen::VectorXd& y) {
    return SurfaceShapeEnergy::element_value(element, Local(y));
  };
  const auto grad = [&](const Eigen::VectorXd& y) {
    Local g;
    SurfaceShapeEnergy::element_gradient(element, Local(y), g);
    return Eigen::VectorXd(g);
  };
  Local g;
  SurfaceShapeEnergy::element_gradient(element, q, g);
  SurfaceShapeEnergy::LocalMatrix h;
  SurfaceShapeEnergy::element_hessian(element, q, false, h);
  CHECK(test::fd_matches(g, test::fd_gradient(f, q), 1e-6));
  CHECK(test::fd_matches(h, test::fd_hessian(grad, q), 1e-6));
  CHECK((h - h.transpose()).norm() <= 1e-12 * h.norm());
}

TEST_CASE("surface shape energy: assembled gradient and Hessian match finite differences",
          "[energies][surface][grad][hess]") {
  const TriangleMesh rest = test::curved_grid(4);
  const DofLayout layout{static_cast<int>(rest.vertices.rows())};
  const SurfaceShapeEnergy energy(rest, layout);
  CHECK(energy.elements().size() == 3 * 3 + 2 * 3 * 2);  // interior edges of a 4×4 grid

  std::srand(7);
  const Eigen::VectorXd x =
      test::flatten(rest.vertices) + 0.1 * Eigen::VectorXd::Random(rest.vertices.size());
  test::check_position_energy(energy, x, 1e-6);
}

TEST_CASE("surface shape energy: zero with zero gradient at rest and under rigid motions",
          "[energies][surface][invariance]") {
  const TriangleMesh rest = GENERATE(test::curved_grid(5), icosphere(1, 0.7));
  const DofLayout layout{static_cast<int>(rest.vertices.rows())};
  const SurfaceShapeEnergy energy(rest, layout);
  REQUIRE(!energy.elements().empty());
  const double angle = GENERATE(0.0, 0.4, 2.5);
  CAPTURE(angle);
  const MatrixX3d moved =
      rigidly_moved(rest.vertices, angle, Vector3d(1, 2, -0.5), Vector3d(3, -1, 2));
  Eigen::VectorXd g;
  energy.gradient(moved, 1.0, g);
  CHECK(energy.value(moved, 1.0) <= 1e-24);
  CHECK(g.norm() <= 1e-12);

  SECTION("a non-rigid deformation costs energy") {
    MatrixX3d bent = moved;
    bent.col(2) += 0.2 * moved.col(0).cwiseAbs2();
    CHECK(energy.value(bent, 1.0) > 1e-6);
  }
}

TEST_CASE("surface shape energy: degenerate rest triangles are left out", "[energies][surface]") {
  TriangleMesh rest;
  rest.vertices.resize(4, 3);
  rest.vertices << 0, 0, 0, 1, 0, 0, 0.5, 0, 0, 0.5, 1, 0;  // first triangle collinear
  rest.faces.resize(2, 3);
  rest.faces << 0, 1, 2, 1, 0, 3;
  const SurfaceShapeEnergy energy(rest, DofLayout{4});
  CHECK(energy.elements().empty());
  CHECK(energy.value(rest.vertices, 1.0) == 0.0);
}

TEST_CASE("surface shape energy: the t-free layout shifts garment dofs by one",
          "[energies][surface]") {
  const TriangleMesh rest = test::curved_grid(3);
  const int n = static_cast<int>(rest.vertices.rows());
  const SurfaceShapeEnergy fixed_t(rest, DofLayout{n, false});
  const SurfaceShapeEnergy free_t(rest, DofLayout{n, true});
  MatrixX3d V = rest.vertices;
  V(4, 2) += 0.1;
  Eigen::VectorXd g_fixed, g_free;
  fixed_t.gradient(V, 1.0, g_fixed);
  free_t.gradient(V, 1.0, g_free);
  REQUIRE(g_free.size() == 3 * n + 1);
  CHECK(g_free[0] == 0.0);
  CHECK((g_free.tail(3 * n) - g_fixed).norm() == 0.0);
  const Eigen::MatrixXd H_free = free_t.hessian(V, 1.0, true);
  const Eigen::MatrixXd H_fixed = fixed_t.hessian(V, 1.0, true);
  CHECK((H_free.bottomRightCorner(3 * n, 3 * n) - H_fixed).norm() == 0.0);
  CHECK(H_free.row(0).norm() == 0.0);
}

TEST_CASE(
    "surface shape energy: the element's PSD Hessian is the exact one plus a PSD "
    "rank-two term, or Gauss–Newton near rest",
    "[energies][surface][hess]") {
  // Near rest the second-order part is negligible and dropped; further away the element
  // keeps the positive part of it, so the PSD Hessian exceeds the exact one by the
  // negative part: PSD, of rank two (±γρ, each twice, in the second-order part).
  const int seed = GENERATE(1, 2, 3);
  const double perturbation = GENERATE(1e-7, 1e-4, 0.3);
  CAPTURE(seed, perturbation);
  const TriangleMesh rest = random_hinge(seed);
  const SurfaceShapeEnergy energy(rest, DofLayout{4});
  REQUIRE(energy.elements().size() == 1);
  const auto& element = energy.elements()[0];
  const SurfaceShapeEnergy::LocalVector q = perturbed_corners(rest, element, perturbation);

  SurfaceShapeEnergy::LocalMatrix exact, psd;
  SurfaceShapeEnergy::element_hessian(element, q, false, exact);
  SurfaceShapeEnergy::element_hessian(element, q, true, psd);
  using Eigen::SelfAdjointEigenSolver;
  const SelfAdjointEigenSolver<SurfaceShapeEnergy::LocalMatrix> psd_eigen(psd);
  const SurfaceShapeEnergy::LocalMatrix excess = psd - exact;
  const SelfAdjointEigenSolver<SurfaceShapeEnergy::LocalMatrix> excess_eigen(excess);
  const double scale = exact.norm();
  CHECK(psd_eigen.eigenvalues().minCoeff() >= -1e-12 * scale);
  if (perturbation < 1e-6) {
    CHECK(excess.norm() <= 1e-5 * scale);
  } else if (excess.norm() > 2e-3 * scale) {
    CHECK(excess_eigen.eigenvalues().minCoeff() >= -1e-10 * scale);
    CHECK((excess_eigen.eigenvalues().array() > 1e-10 * scale).count() == 2);
  }
  if (perturbation == 0.3) CHECK(excess.norm() > 2e-3 * scale);
}
