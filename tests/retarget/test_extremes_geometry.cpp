#include <algorithm>
#include <filesystem>
#include <string>

#include <fmt/format.h>
#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include "core/io/mesh_file.hpp"
#include "core/io/obj_document.hpp"
#include "extremes_support.hpp"

namespace fs = std::filesystem;
using namespace gr;

namespace {

/// A flat 8×8 patch of side 1 at z = 0.9375 over the top of a UV sphere (z = 1): the
/// sphere pokes through it, so the shrink must erode the avatar below the patch and the
/// inflation must raise a tent. Every coordinate is dyadic and the normalization is the
/// identity, so the inputs reach the solver exactly as written.
TriangleMesh tent_patch() { return test::flat_patch(8, 0.125, 0.9375); }

TriangleMesh tent_avatar() { return test::uv_sphere(16, 9); }

/// Face (a, b, d) of the patch's square (3, 3), away from the boundary.
constexpr int kInteriorFace = 2 * (3 * 8 + 3);

/// The tent's fit creeps (RMS gradient about 5e-3 after 1000 steps: the patch's free
/// corners barely touch the sphere), so these runs ask for a looser fit tolerance.
constexpr double kTentTolerance = 1e-2;

RetargetOptions tent_scene(const std::string& name, const TriangleMesh& garment) {
  RetargetOptions options = test::synthetic_scene(name, garment, tent_avatar());
  options.overrides.set("eps_tol", kTentTolerance);
  return options;
}

RetargetResult run_tent(const std::string& name, const TriangleMesh& garment) {
  return test::run_and_check(tent_scene(name, garment));
}

}  // namespace

TEST_CASE("extremes: the tent scene without defects is certified",
          "[pipeline][extremes][geometry]") {
  const RetargetResult result = run_tent("tent", tent_patch());
  INFO(result.message);
  CHECK(result.status == Outcome::kCertified);
}

TEST_CASE("extremes: a sliver triangle of aspect ratio 1e6 in the garment",
          "[pipeline][extremes][geometry][heavy]") {
  const TriangleMesh garment = test::with_sliver(tent_patch(), kInteriorFace, 1e-6);
  const Eigen::Index sliver = garment.faces.rows() - 1;
  const Vector3d a = garment.vertices.row(garment.faces(sliver, 0)).transpose();
  const Vector3d b = garment.vertices.row(garment.faces(sliver, 1)).transpose();
  const Vector3d m = garment.vertices.row(garment.faces(sliver, 2)).transpose();
  const double aspect = (b - a).squaredNorm() / (b - a).cross(m - a).norm();
  CAPTURE(aspect);
  REQUIRE(aspect == Approx(1e6).epsilon(1e-3));
  const RetargetResult result = run_tent("sliver", garment);
  INFO(result.message);
  // Rounding to the normalized lattice would fold the sliver: exact coordinates are kept.
  CHECK(result.report.normalize.lattice == 0.0);
  // The sliver's rest frame makes the shape energy stiff by its aspect ratio across one
  // edge: the inflation still snaps, but the fit may stall at its cap; the garment is then
  // still certified and the report says the fit is incomplete, naming the knobs.
  CHECK(result.report.inflate.status == "snapped");
  REQUIRE(result.status == Outcome::kCertified);
  if (result.report.fit.status != "converged") {
    REQUIRE_FALSE(result.report.warnings.empty());
    CHECK_THAT(result.report.warnings.back(), Catch::Contains("--max-newton-iterations"));
  }
}

TEST_CASE("extremes: an exactly collinear (zero-area) garment face with distinct corners",
          "[pipeline][extremes][geometry]") {
  // The middle corner lies exactly on the edge the face shares with its neighbour, so the
  // split faces touch that neighbour along a segment: the garment touches itself as given.
  // The untangle pushes the touching pairs apart before the solve; what it leaves is
  // inherited, and the run certifies that it adds none.
  const RetargetOptions options = test::synthetic_scene(
      "collinear", test::with_sliver(tent_patch(), kInteriorFace, 0.0), tent_avatar());
  const RetargetResult result = run_retarget(options);
  INFO(result.message);
  const UntangleReport& untangled = result.report.repairs.untangle;
  CHECK(untangled.pairs > 0);
  CHECK(untangled.pairs == untangled.resolved + untangled.left);
  CHECK(result.report.repairs.crossings.pairs == untangled.remaining);
  CHECK(result.status == Outcome::kCertified);
}

TEST_CASE("extremes: a zero-area garment face on a repeated vertex",
          "[pipeline][extremes][geometry]") {
  TriangleMesh garment = tent_patch();
  garment.faces.conservativeResize(garment.faces.rows() + 1, 3);
  garment.faces.row(garment.faces.rows() - 1) << 30, 30, 31;
  const RetargetOptions options = tent_scene("repeated_vertex", garment);
  const RetargetResult result = test::run_and_check(options);
  INFO(result.message);
  CHECK(result.status == Outcome::kCertified);
  bool warned = false;
  for (const auto& warning : result.report.warnings)
    warned = warned || warning.find("zero-area") != std::string::npos;
  CHECK(warned);
}

TEST_CASE("extremes: duplicate garment vertices (a seam and unreferenced copies) are welded",
          "[pipeline][extremes][geometry]") {
  const TriangleMesh patch = tent_patch();
  RetargetOptions options = tent_scene("duplicates", patch);
  // Every vertex written twice; faces right of x = 0 use the second copies, so the seam
  // on x = 0 is made of bit-identical pairs and half of all vertices are unreferenced.
  const auto n = patch.vertices.rows();
  TriangleMesh doubled;
  doubled.vertices.resize(2 * n, 3);
  doubled.vertices << patch.vertices, patch.vertices;
  doubled.faces = patch.faces;
  for (Eigen::Index f = 0; f < patch.faces.rows(); ++f) {
    double x = 0.0;
    for (int k = 0; k < 3; ++k) x += patch.vertices(patch.faces(f, k), 0);
    if (x > 0.0) doubled.faces.row(f).array() += static_cast<int>(n);
  }
  write_obj(options.inputs.garment, doubled);
  const RetargetResult result = test::run_and_check(options);
  INFO(result.message);
  REQUIRE(result.status == Outcome::kCertified);
  CHECK(result.report.normalize.garment_vertices == n);
  // The seam stays closed: both copies of each referenced seam vertex end in one place.
  const ObjDocument written = read_obj(result.garment_path);
  int seam = 0;
  for (Eigen::Index v = 0; v < n; ++v)
    if (patch.vertices(v, 0) == 0.0) {
      ++seam;
      CHECK(written.positions.row(v) == written.positions.row(v + n));
    }
  CHECK(seam == 9);
}

TEST_CASE("extremes: garment edges within 1e-10 rad of parallel to avatar edges, inside dhat",
          "[pipeline][extremes][geometry]") {
  // The cap has the avatar's connectivity, 1e-3 outside (half of dhat), turned by 1e-10
  // rad: every cap edge runs nearly parallel to an avatar edge within the barrier's reach.
  TriangleMesh cap = test::cap_at_gap(1e-3);
  cap.vertices = (cap.vertices * Eigen::AngleAxisd(1e-10, Vector3d(0.3, 0.2, 1.0).normalized())
                                     .toRotationMatrix()
                                     .transpose())
                     .eval();
  const RetargetResult result = test::run_and_check(test::synthetic_scene("parallel", cap));
  INFO(result.message);
  CHECK(result.status == Outcome::kCertified);
}

TEST_CASE("extremes: a garment vertex exactly on an avatar edge is resolved by the shrink",
          "[pipeline][extremes][geometry]") {
  // Touching counts as intersecting for every exact check. The shrunk avatar follows the
  // smoothed level set, whose zero level passes inside the octahedron's sharp edges, so it
  // is certified free of the garment and the inflation lifts the garment off the edge.
  // A fan of six triangles around (0.5, 0.5, 0), the midpoint of the octahedron's edge
  // from (1, 0, 0) to (0, 1, 0); the ring leans outward so only the centre touches.
  TriangleMesh fan;
  fan.vertices.resize(7, 3);
  const Vector3d centre(0.5, 0.5, 0.0);
  const Vector3d out = Vector3d(1.0, 1.0, 0.0) / 8.0;
  const Vector3d along(0.25, -0.25, 0.0);
  const Vector3d up(0.0, 0.0, 0.25);
  fan.vertices.row(0) = centre.transpose();
  for (int k = 0; k < 6; ++k) {
    const double angle = k * M_PI / 3.0;
    fan.vertices.row(k + 1) =
        (centre + out + std::cos(angle) * along + std::sin(angle) * up).transpose();
  }
  fan.faces.resize(6, 3);
  for (int k = 0; k < 6; ++k) fan.faces.row(k) << 0, 1 + k, 1 + (k + 1) % 6;
  const RetargetResult result =
      test::run_and_check(test::synthetic_scene("on_edge", fan, test::octahedron()));
  INFO(result.message);
  CHECK(result.status == Outcome::kCertified);
}
