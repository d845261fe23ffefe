#include <cmath>
#include <random>
#include <vector>

#include <tbb/parallel_for.h>
#include <catch2/catch.hpp>

#include "core/mesh/primitives.hpp"
#include "shrink/level_set/grid_distance_field.hpp"
#include "shrink/level_set/signed_distance_grid.hpp"
#include "shrink/level_set/triangle_tree.hpp"
#include "shrink/shrunk_avatar/levelset_shrink.hpp"
#include "shrink_oracles.hpp"

using namespace gr;

TEST_CASE("signed distance voxels of a sphere are exact mesh distances", "[shrink][sdf]") {
  const TriangleMesh sphere = uv_sphere(0.5, Vector3d(0.013, -0.021, 0.007));
  const double h = 0.02;
  const SignedDistanceGrid grid = build_signed_distance(sphere, h);
  REQUIRE(grid.background() == Approx(0.1).margin(1e-6));
  // Full depth inside: the centre is about a radius deep.
  REQUIRE(grid.min_value() < -0.48);
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> index(-32, 32);
  int checked_inside = 0, checked_band = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const Eigen::Vector3i ijk(index(rng), index(rng), index(rng));
    const Vector3d p = h * ijk.cast<double>();
    const double value = grid.voxel_value(ijk);
    const double distance = test::brute_force_distance(sphere, p);
    const bool inside = test::brute_force_winding_number(sphere, p) > 0.5;
    CAPTURE(p.transpose(), value, distance, inside);
    if (inside) {
      REQUIRE(value == Approx(-distance).margin(1e-5));
      ++checked_inside;
    } else if (distance < grid.background() - 2 * h) {
      REQUIRE(value == Approx(distance).margin(1e-5));
      ++checked_band;
    } else if (distance > grid.background()) {
      REQUIRE(value == Approx(grid.background()));
    }
  }
  CHECK(checked_inside > 50);
  CHECK(checked_band > 20);
}

TEST_CASE("an inverted mesh gets the same signed distance", "[shrink][sdf]") {
  TriangleMesh sphere = uv_sphere(0.4, Vector3d::Zero(), 12, 24);
  const SignedDistanceGrid outward = build_signed_distance(sphere, 0.05);
  sphere.faces.col(1).swap(sphere.faces.col(2));
  const SignedDistanceGrid inward = build_signed_distance(sphere, 0.05);
  for (int i = -10; i <= 10; ++i) {
    const Eigen::Vector3i ijk(i, i / 2, 1);
    REQUIRE(inward.voxel_value(ijk) == outward.voxel_value(ijk));
  }
  REQUIRE(outward.voxel_value(Eigen::Vector3i::Zero()) < -0.35);
}

TEST_CASE("a narrow-band grid keeps the band and holds -background deeper inside",
          "[shrink][sdf]") {
  const TriangleMesh sphere = uv_sphere(0.5, Vector3d(0.013, -0.021, 0.007), 16, 32);
  const double h = 0.02;
  const SignedDistanceGrid full = build_signed_distance(sphere, h);
  SignedDistanceOptions narrow_options;
  narrow_options.full_depth = false;
  const SignedDistanceGrid narrow = build_signed_distance(sphere, h, narrow_options);
  REQUIRE(full.full_depth());
  REQUIRE_FALSE(narrow.full_depth());
  REQUIRE(narrow.min_value() > -narrow.background() - 1e-6);
  REQUIRE(narrow.active_voxel_count() < full.active_voxel_count());
  int deep = 0;
  for (int i = -30; i <= 30; ++i)
    for (int j = -30; j <= 30; j += 3) {
      const Eigen::Vector3i ijk(i, j, 1);
      const double value = full.voxel_value(ijk);
      CAPTURE(ijk.transpose(), value, narrow.voxel_value(ijk));
      // OpenVDB's band ends within a voxel of the background value.
      if (value > -full.background() + h) {
        REQUIRE(narrow.voxel_value(ijk) == value);
      } else if (value < -full.background()) {
        REQUIRE(narrow.voxel_value(ijk) == Approx(-narrow.background()));
        ++deep;
      }
    }
  CHECK(deep > 50);
  // A garment 0.2 deep needs an erosion below the band: the narrow grid says so, and the
  // full-depth grid finds it.
  const TriangleMesh deep_garment = uv_sphere(0.3, Vector3d::Zero(), 6, 12);
  REQUIRE_THROWS_AS(shrink_levelset(sphere, deep_garment, narrow), ShrinkBandTooShallowError);
  CHECK(shrink_levelset(sphere, deep_garment, full).depth > narrow.background());
}

namespace {

/// Central finite differences of the field's value (for the gradient) and gradient (for
/// the Hessian).
void check_derivatives(const GridDistanceField& field, const Vector3d& p, double step) {
  Vector3d gradient;
  Eigen::Matrix3d hessian;
  field.evaluate(p, &gradient, &hessian);
  Vector3d fd_gradient;
  Eigen::Matrix3d fd_hessian;
  for (int a = 0; a < 3; ++a) {
    const Vector3d e = step * Vector3d::Unit(a);
    Vector3d g_plus, g_minus;
    fd_gradient[a] =
        (field.evaluate(p + e, &g_plus) - field.evaluate(p - e, &g_minus)) / (2 * step);
    fd_hessian.col(a) = (g_plus - g_minus) / (2 * step);
  }
  CAPTURE(p.transpose(), gradient.transpose(), fd_gradient.transpose(), hessian, fd_hessian);
  REQUIRE((gradient - fd_gradient).norm() <= 1e-6 * (1.0 + gradient.norm()));
  REQUIRE((hessian - fd_hessian).norm() <= 1e-4 * (1.0 + hessian.norm()));
  REQUIRE((hessian - hessian.transpose()).norm() <= 1e-12 * (1.0 + hessian.norm()));
}

}  // namespace

TEST_CASE("tricubic sampler: gradient and Hessian match finite differences",
          "[shrink][sdf][grad]") {
  const TriangleMesh sphere = uv_sphere(0.5, Vector3d(0.01, 0.02, -0.03), 16, 32);
  const GridDistanceField field(build_signed_distance(sphere, 0.04, {0.12, {}}));
  SECTION("inside, on the surface and in the band") {
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> coordinate(-0.65, 0.65);
    for (int trial = 0; trial < 60; ++trial)
      check_derivatives(field, Vector3d(coordinate(rng), coordinate(rng), coordinate(rng)), 1e-5);
  }
  SECTION("on the plateau and beyond the grid's box") {
    const double distance = GENERATE(0.8, 1.2, 3.0, 50.0);
    const Vector3d p = distance * Vector3d(0.61, -0.47, 0.637);
    check_derivatives(field, p, 1e-5 * distance);
  }
}

TEST_CASE("tricubic sampler: extrapolation keeps growing, sign and threads", "[shrink][sdf]") {
  const TriangleMesh sphere = uv_sphere(0.5, Vector3d::Zero(), 16, 32);
  const SignedDistanceGrid grid = build_signed_distance(sphere, 0.04);
  const GridDistanceField field(grid);
  REQUIRE(field.evaluate(Vector3d::Zero()) < -0.45);
  // Between the band (0.62) and the grid's box (three voxels beyond it): the background.
  double previous = field.evaluate(Vector3d(0.7, 0.0, 0.0));
  REQUIRE(previous == Approx(grid.background()));
  for (double x = 1.5; x < 100.0; x *= 1.5) {
    Vector3d gradient;
    const double value = field.evaluate(Vector3d(x, 0.2 * x, 0.0), &gradient);
    REQUIRE(std::isfinite(value));
    REQUIRE(value > previous);
    REQUIRE(gradient.norm() <= 1.0 + 1e-9);
    previous = value;
  }
  Vector3d far_gradient;
  field.evaluate(Vector3d(1e3, 0.0, 0.0), &far_gradient);
  REQUIRE(far_gradient.x() == Approx(1.0).margin(1e-6));

  // Evaluations from many threads give the serial answers bit for bit.
  std::vector<Vector3d> points;
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> coordinate(-0.8, 0.8);
  for (int i = 0; i < 2000; ++i)
    points.emplace_back(coordinate(rng), coordinate(rng), coordinate(rng));
  std::vector<double> serial(points.size()), parallel(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) serial[i] = field.evaluate(points[i]);
  tbb::parallel_for(std::size_t(0), points.size(), [&](std::size_t i) {
    Vector3d g;
    Eigen::Matrix3d H;
    parallel[i] = field.evaluate(points[i], &g, &H);
  });
  REQUIRE(serial == parallel);
}

TEST_CASE("signed distance rejects a bad voxel size", "[shrink][sdf]") {
  const TriangleMesh sphere = uv_sphere(0.5, Vector3d::Zero(), 8, 16);
  REQUIRE_THROWS_AS(build_signed_distance(sphere, 0.0), std::invalid_argument);
  REQUIRE_THROWS_AS(build_signed_distance(sphere, std::nan("")), std::invalid_argument);
}
