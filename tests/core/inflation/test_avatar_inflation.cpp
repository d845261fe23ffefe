#include <catch2/catch.hpp>

#include "core/energies/analytic_fields.hpp"
#include "core/fit/garment_fit.hpp"
#include "core/inflation/avatar_inflation.hpp"
#include "core/inflation/synthetic_scene.hpp"

using namespace gr;

namespace {

/// Smallest signed distance of the points to the planes of a convex, outward-oriented
/// polyhedron's faces, maximized over faces: positive iff the point is outside.
double min_outside_distance(const TriangleMesh& convex, const Eigen::Ref<const MatrixX3d>& points) {
  double smallest = std::numeric_limits<double>::infinity();
  for (Eigen::Index p = 0; p < points.rows(); ++p) {
    double outside = -std::numeric_limits<double>::infinity();
    for (Eigen::Index f = 0; f < convex.faces.rows(); ++f) {
      const Vector3d a = convex.vertices.row(convex.faces(f, 0)).transpose();
      const Vector3d b = convex.vertices.row(convex.faces(f, 1)).transpose();
      const Vector3d c = convex.vertices.row(convex.faces(f, 2)).transpose();
      const Vector3d n = (b - a).cross(c - a).normalized();
      outside = std::max(outside, n.dot(points.row(p).transpose() - a));
    }
    smallest = std::min(smallest, outside);
  }
  return smallest;
}

/// Smallest distance between the garment and the avatar (and the garment and itself) over
/// pairs closer than `radius`, with the core's own distance code.
double contact_distance(const GarmentScene& scene, const Eigen::Ref<const MatrixX3d>& garment,
                        double radius) {
  const ContactMesh mesh = ContactMesh::build(scene.garment, scene.avatar, true);
  MatrixX3d V(mesh.vertex_count(), 3);
  V.topRows(garment.rows()) = garment;
  V.bottomRows(scene.avatar.vertices.rows()) = scene.avatar.vertices;
  const BarrierPotential barrier(0.002, V);
  return barrier.minimum_distance(find_candidates(mesh, V, radius), V);
}

}  // namespace

TEST_CASE("avatar inflation: a sphere garment around an inflating sphere avatar",
          "[inflation][integration]") {
  const GarmentScene scene = test::inflating_sphere_scene();
  REQUIRE(min_outside_distance(scene.avatar, scene.garment.vertices) < 0.0);  // A cuts the garment
  RetargetParameters parameters;
  int rounds = 0;
  const InflationResult result =
      inflate_avatar(scene, parameters, [&](const InflationRound& round) { rounds = round.round; });
  INFO(result.message);
  REQUIRE(result.status == InflationStatus::kSnapped);
  CHECK(result.t == 1.0);
  CHECK(result.rounds == rounds);
  CHECK(result.newton_iterations > 0);
  CHECK(std::abs(result.t_before_snap - 1.0) < 1e-3);
  // Pushed outside the (convex) avatar, at a positive distance from it.
  CHECK(min_outside_distance(scene.avatar, result.garment) > 0.0);
  CHECK(contact_distance(scene, result.garment, 0.05) > 0.0);

  SECTION("the fit pulls the garment towards the avatar and keeps it outside") {
    const test::SphereField field(Vector3d::Zero(), 1.0);
    GarmentScene fit_scene = scene;
    fit_scene.distance_field = &field;
    const FitResult fit = fit_garment(fit_scene, result.garment, parameters);
    INFO(fit.solve.message);
    CHECK(fit.solve.status != SolverStatus::kNonFiniteEnergy);
    CHECK(fit.solve.iterations > 0);
    const auto mean_radius = [](const MatrixX3d& V) { return V.rowwise().norm().mean(); };
    CHECK(mean_radius(fit.garment) < mean_radius(result.garment));
    CHECK(min_outside_distance(scene.avatar, fit.garment) > 0.0);
    CHECK(contact_distance(scene, fit.garment, 0.05) > 0.0);
  }
}

TEST_CASE("avatar inflation: a round that leaves t < 0 (eta < 0) resets and recovers",
          "[inflation][integration]") {
  // The garment starts within dhat of A0 all around (same connectivity, radius 0.9 against
  // 0.899), it is stiff (large w_surf) and the penalty on t starts weak: the first solve
  // relieves the barrier by shrinking the avatar further (t < 0, so |1 - t| > 1 and
  // eta < 0) rather than by stretching the garment.
  GarmentScene scene;
  scene.avatar = icosphere(1, 1.0);
  scene.shrunk_avatar = 0.899 * scene.avatar.vertices;
  scene.garment = icosphere(1, 0.9);
  RetargetParameters parameters;
  parameters.w_surf = 1e6;
  std::vector<InflationRound> rounds;
  const InflationResult result = inflate_avatar(
      scene, parameters, [&](const InflationRound& round) { rounds.push_back(round); });
  INFO(result.message);
  REQUIRE(!rounds.empty());
  CHECK(rounds.front().t < 0.0);
  CHECK(rounds.front().eta < 0.0);
  CHECK(rounds.front().reset);
  // Reset doubles lambda1, and eta < 0.99 doubles it again.
  CHECK(rounds.front().lambda1 == Approx(4.0));
  CHECK(result.resets >= 1);
  REQUIRE(result.status == InflationStatus::kSnapped);
  CHECK(result.t == 1.0);
  CHECK(min_outside_distance(scene.avatar, result.garment) > 0.0);
}

TEST_CASE("garment problem: the inflation's goal is a valid snap near t = 1, the fit has none",
          "[inflation]") {
  const GarmentScene scene = test::inflating_sphere_scene();
  RetargetParameters parameters;
  GarmentProblem inflation(scene, parameters, GarmentProblem::Stage::kInflation);
  const DofLayout& layout = inflation.layout();
  Eigen::VectorXd x = layout.pack(0.0, scene.garment.vertices);
  // At t = 0 snapping would carry the avatar through the garment, and t is far from 1.
  CHECK_FALSE(inflation.goal_reached(x));
  const InflationResult inflated = inflate_avatar(scene, parameters);
  REQUIRE(inflated.status == InflationStatus::kSnapped);
  const double window = inflation.snap_window();
  REQUIRE(window > 0.0);
  x = layout.pack(1.0 - 0.5 * window, inflated.garment);
  CHECK(inflation.goal_reached(x));
  // Out of the window, even where snapping is valid.
  x = layout.pack(1.0 - 2.0 * window, inflated.garment);
  CHECK(inflation.is_valid_snapping(x));
  CHECK_FALSE(inflation.goal_reached(x));

  const test::SphereField field(Vector3d::Zero(), 1.0);
  GarmentScene fit_scene = scene;
  fit_scene.distance_field = &field;
  GarmentProblem fit(fit_scene, parameters, GarmentProblem::Stage::kFit);
  CHECK_FALSE(fit.goal_reached(fit.layout().pack(1.0, inflated.garment)));
}

TEST_CASE("avatar inflation: a garment pinched between two growing parts stops as stalled",
          "[inflation][integration]") {
  // A sphere garment around one sphere part of the avatar; a second part outside it grows
  // into the first (their full sizes overlap), so the garment between them has no room and t
  // cannot reach 1.
  GarmentScene scene = test::inflating_sphere_scene(1, 2);
  const TriangleMesh inner = scene.avatar;
  TriangleMesh outer = icosphere(1, 1.0);
  const Vector3d outer_centre(1.6, 0.0, 0.0);
  outer.vertices.rowwise() += outer_centre.transpose();
  scene.avatar.vertices.resize(inner.vertices.rows() + outer.vertices.rows(), 3);
  scene.avatar.vertices << inner.vertices, outer.vertices;
  scene.avatar.faces.resize(inner.faces.rows() + outer.faces.rows(), 3);
  scene.avatar.faces << inner.faces, (outer.faces.array() + inner.vertices.rows()).matrix();
  MatrixX3d outer_shrunk = 0.3 * icosphere(1, 1.0).vertices;
  outer_shrunk.rowwise() += outer_centre.transpose();
  scene.shrunk_avatar.resize(scene.avatar.vertices.rows(), 3);
  scene.shrunk_avatar << 0.5 * inner.vertices, outer_shrunk;

  RetargetParameters parameters;
  parameters.newton.max_iterations = 100;
  const InflationResult result = inflate_avatar(scene, parameters);
  INFO(result.message);
  CHECK(result.status == InflationStatus::kStalled);
  CHECK(result.rounds < parameters.max_al_rounds);
  CHECK(result.t < 1.0);
}
