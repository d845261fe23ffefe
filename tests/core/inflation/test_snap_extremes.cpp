#include <cmath>

#include <catch2/catch.hpp>

#include "core/inflation/avatar_inflation.hpp"
#include "core/test_shapes.hpp"

using namespace gr;

namespace {

/// The avatar A: a unit icosphere; A0 = A / 2; the garment: A blown up by 1 + gap about
/// the centre (same connectivity, so every garment vertex is `gap` from A and every
/// garment edge parallel to an avatar edge).
GarmentScene blown_up_scene(double gap) {
  GarmentScene scene;
  scene.avatar = icosphere(1, 1.0);
  scene.shrunk_avatar = 0.5 * scene.avatar.vertices;
  scene.garment = scene.avatar;
  scene.garment.vertices *= 1.0 + gap;
  return scene;
}

}  // namespace

TEST_CASE("snap: t within 1e-12 of 1 snaps when the garment is clear of A, never across it",
          "[inflation][snap][extremes]") {
  const double t = GENERATE(1.0 - 1e-12, 1.0 - 1e-15, 1.0, 1.0 + 1e-12);
  CAPTURE(t);
  const RetargetParameters parameters;

  SECTION("garment 1e-9 outside A: the snap moves the avatar by < 1e-12 and is valid") {
    const GarmentScene scene = blown_up_scene(1e-9);
    GarmentProblem problem(scene, parameters, GarmentProblem::Stage::kInflation);
    const Eigen::VectorXd x = problem.layout().pack(t, scene.garment.vertices);
    CHECK(problem.is_valid_snapping(x));
    CHECK(std::isfinite(problem.value(x)));
  }

  SECTION("garment 1e-13 inside A but outside A(t): snapping would cross it, refused") {
    if (t >= 1.0) return;  // A(t) already contains the garment: not a state the solver reaches
    // A(t) has radius (1 + t) / 2 at the vertices: 1 - 5e-13 for t = 1 - 1e-12.
    // For t = 1 - 1e-15 the garment is A itself: the snap would end touching it.
    const double gap = t < 1.0 - 1e-13 ? -1e-13 : 0.0;
    const GarmentScene scene = blown_up_scene(gap);
    GarmentProblem problem(scene, parameters, GarmentProblem::Stage::kInflation);
    const Eigen::VectorXd x = problem.layout().pack(t, scene.garment.vertices);
    CHECK_FALSE(problem.is_valid_snapping(x));
  }

  SECTION("eta and the multiplier stay finite and the AL pulls t towards 1") {
    const double eta = 1.0 - std::sqrt(std::abs(1.0 - t));
    CHECK(eta > 0.99);
    AvatarConstraint al{1.0, 1.0, 0.0};
    al.update_multiplier(t);
    CHECK(std::isfinite(al.lambda2));
    CHECK(std::abs(al.lambda2) <= 2e-12);
    CHECK(std::isfinite(al.derivative(t)));
    CHECK((t - 1.0) * al.derivative(t) >= 0.0);  // descent moves t towards 1
  }
}
