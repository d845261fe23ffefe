#include <atomic>

#include <catch2/catch.hpp>

#include <Eigen/Dense>

#include "core/energies/analytic_fields.hpp"
#include "core/energies/energy_checks.hpp"
#include "core/energies/fit_energy.hpp"
#include "core/test_shapes.hpp"

using namespace gr;

TEST_CASE("triangle quadrature rules integrate polynomials exactly", "[energies][fit]") {
  const auto mean = [](const TriangleQuadrature& rule, int power) {
    double sum = 0.0;
    for (std::size_t q = 0; q < rule.weights.size(); ++q)
      sum += rule.weights[q] * std::pow(rule.barycentric[q][0], power);
    return sum;
  };
  for (int count : {1, 3, 6}) {
    const auto rule = TriangleQuadrature::with_points(count);
    CAPTURE(count);
    CHECK(rule.weights.size() == static_cast<std::size_t>(count));
    CHECK(mean(rule, 0) == Approx(1.0).epsilon(1e-14));
    CHECK(mean(rule, 1) == Approx(1.0 / 3.0).epsilon(1e-14));
  }
  // Mean of b0^2 over a triangle is 1/6, of b0^4 is 1/15.
  CHECK(mean(TriangleQuadrature::with_points(3), 2) == Approx(1.0 / 6.0).epsilon(1e-14));
  CHECK(mean(TriangleQuadrature::with_points(6), 4) == Approx(1.0 / 15.0).epsilon(1e-12));
  CHECK_THROWS_AS(TriangleQuadrature::with_points(4), std::invalid_argument);
}

TEST_CASE("fit energy: gradient and Hessian match finite differences",
          "[energies][fit][grad][hess]") {
  const int samples = GENERATE(1, 3, 6);
  CAPTURE(samples);
  // A sphere patch partly outside a unit sphere: some points with phi > 0, some inside.
  const TriangleMesh rest = icosphere(1, 1.05);
  const test::SphereField field(Vector3d(0.1, 0.0, 0.0), 1.0);
  const DofLayout layout{static_cast<int>(rest.vertices.rows())};
  const FitEnergy energy(rest, {}, field, samples, layout);
  CHECK(energy.fit_face_count() == rest.faces.rows());

  std::srand(11);
  const Eigen::VectorXd x =
      test::flatten(rest.vertices) + 0.02 * Eigen::VectorXd::Random(rest.vertices.size());
  test::check_position_energy(energy, x, 1e-5);
}

TEST_CASE("fit energy with ease offsets: gradient and Hessian match finite differences",
          "[energies][fit][ease][grad][hess]") {
  const int samples = GENERATE(1, 3, 6);
  CAPTURE(samples);
  // Points both nearer and farther than their targets, and some targets of 0.
  const TriangleMesh rest = icosphere(1, 1.05);
  const test::SphereField field(Vector3d(0.1, 0.0, 0.0), 1.0);
  const DofLayout layout{static_cast<int>(rest.vertices.rows())};
  std::vector<double> offsets(static_cast<std::size_t>(rest.vertices.rows()));
  for (std::size_t v = 0; v < offsets.size(); ++v) offsets[v] = v % 4 == 0 ? 0.0 : 0.01 * (v % 9);
  const FitEnergy energy(rest, {}, field, samples, layout, offsets);
  std::srand(12);
  const Eigen::VectorXd x =
      test::flatten(rest.vertices) + 0.02 * Eigen::VectorXd::Random(rest.vertices.size());
  test::check_position_energy(energy, x, 1e-5);
}

TEST_CASE("fit energy with ease offsets holds a face at its distance from both sides",
          "[energies][fit][ease]") {
  TriangleMesh face;
  face.vertices.resize(3, 3);
  face.vertices << 0, 0, 0.5, 1, 0, 0.5, 0, 1, 0.5;
  face.faces.resize(1, 3);
  face.faces << 0, 1, 2;
  const double R = 1e6;  // phi = z - 0.2 near the face
  const test::SphereField field(Vector3d(0.25, 0.25, 0.2 - R), R);
  const FitEnergy energy(face, {}, field, 3, DofLayout{3}, {0.1, 0.1, 0.1});
  // phi = 0.3 against a target of 0.1: 0.5 · 0.2².
  CHECK(energy.value(face.vertices, 1.0) == Approx(0.5 * 0.04).epsilon(1e-6));
  MatrixX3d at_target = face.vertices;
  at_target.col(2).array() -= 0.2;
  CHECK(energy.value(at_target, 1.0) == Approx(0.0).margin(1e-12));
  // Nearer than its target, the face is pushed back out; a tight fit would leave it.
  MatrixX3d nearer = face.vertices;
  nearer.col(2).array() -= 0.25;
  CHECK(energy.value(nearer, 1.0) == Approx(0.5 * 0.05 * 0.05).epsilon(1e-4));
  const FitEnergy tight(face, {}, field, 3, DofLayout{3});
  CHECK(tight.value(nearer, 1.0) == Approx(0.5 * 0.05 * 0.05).epsilon(1e-4));
  nearer.col(2).array() -= 0.1;  // inside: phi = -0.05
  CHECK(tight.value(nearer, 1.0) == 0.0);
  CHECK(energy.value(nearer, 1.0) == Approx(0.5 * 0.15 * 0.15).epsilon(1e-6));
  CHECK_THROWS_AS(FitEnergy(face, {}, field, 3, DofLayout{3}, {0.1}), std::invalid_argument);
}

TEST_CASE("fit energy: zero inside the avatar - the exact value on a flat face",
          "[energies][fit]") {
  TriangleMesh face;
  face.vertices.resize(3, 3);
  face.vertices << 0, 0, 0.5, 1, 0, 0.5, 0, 1, 0.5;
  face.faces.resize(1, 3);
  face.faces << 0, 1, 2;
  // phi = z - 0.2 near the face: a huge sphere below it.
  const double R = 1e6;
  const test::SphereField field(Vector3d(0.25, 0.25, 0.2 - R), R);
  const FitEnergy energy(face, {}, field, 3, DofLayout{3});
  // Constant phi = 0.3 over an area 0.5 face: 0.5 · 0.09.
  CHECK(energy.value(face.vertices, 1.0) == Approx(0.045).epsilon(1e-6));
  MatrixX3d inside = face.vertices;
  inside.col(2).array() -= 0.6;
  CHECK(energy.value(inside, 1.0) == 0.0);
}

TEST_CASE("fit energy: faces with all three vertices listed as no-fit are left out",
          "[energies][fit]") {
  const TriangleMesh rest = test::curved_grid(3);  // 8 faces
  const test::SphereField field(Vector3d(0, 0, -5), 1.0);
  const FitEnergy some(rest, {0, 1, 3, 4}, field, 1, DofLayout{9});
  CHECK(some.fit_face_count() == 6);  // faces (0,1,4) and (0,4,3) are no-fit
  const FitEnergy none(rest, {0, 1, 2, 3, 4, 5, 6, 7, 8}, field, 1, DofLayout{9});
  CHECK(none.fit_face_count() == 0);
  CHECK(none.value(rest.vertices, 1.0) == 0.0);
}

namespace {

/// A distance field that counts its samples.
class CountingField : public DistanceField {
 public:
  explicit CountingField(const DistanceField& field) : field_(field) {}
  double evaluate(const Vector3d& p, Vector3d* gradient, Eigen::Matrix3d* hessian) const override {
    ++count;
    return field_.evaluate(p, gradient, hessian);
  }
  mutable std::atomic<int> count{0};

 private:
  const DistanceField& field_;
};

}  // namespace

TEST_CASE("fit energy: one sampling per iterate serves gradient, Hessian and value",
          "[energies][fit]") {
  const TriangleMesh rest = icosphere(1, 1.05);
  const test::SphereField sphere(Vector3d(0.1, 0.0, 0.0), 1.0);
  const CountingField field(sphere);
  const DofLayout layout{static_cast<int>(rest.vertices.rows())};
  const FitEnergy cached(rest, {}, field, 3, layout);
  const int points = 3 * cached.fit_face_count();
  MatrixX3d moved = rest.vertices;
  moved.col(0).array() += 0.01;

  Eigen::VectorXd g;
  cached.gradient(rest.vertices, 1.0, g);
  const double from_gradient = cached.value(rest.vertices, 1.0);
  CHECK(field.count == points);
  const Eigen::SparseMatrix<double> H = cached.hessian(rest.vertices, 1.0, true);
  CHECK(cached.value(rest.vertices, 1.0) == from_gradient);
  CHECK(field.count == points);  // the Hessian and the value reused the gradient's samples
  const double at_moved = cached.value(moved, 1.0);
  CHECK(field.count == 2 * points);
  CHECK(cached.value(rest.vertices, 1.0) == from_gradient);  // a line-search point keeps them
  CHECK(field.count == 2 * points);

  // Same numbers as an energy that samples afresh for each call.
  const FitEnergy fresh(rest, {}, sphere, 3, layout);
  Eigen::VectorXd g_fresh;
  fresh.gradient(moved, 1.0, g_fresh);  // sampled at another point first
  CHECK(fresh.value(rest.vertices, 1.0) == from_gradient);
  CHECK(fresh.value(moved, 1.0) == at_moved);
  fresh.gradient(rest.vertices, 1.0, g_fresh);
  CHECK(g_fresh == g);
  CHECK((Eigen::MatrixXd(fresh.hessian(rest.vertices, 1.0, true)) - Eigen::MatrixXd(H)).norm() ==
        0.0);
  const Eigen::SparseMatrix<double> H_moved = cached.hessian(moved, 1.0, true);
  CHECK(field.count == 3 * points);
  CHECK((Eigen::MatrixXd(fresh.hessian(moved, 1.0, true)) - Eigen::MatrixXd(H_moved)).norm() ==
        0.0);
}
