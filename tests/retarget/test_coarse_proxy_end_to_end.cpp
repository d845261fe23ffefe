// The coarse proxy through the whole pipeline: a dense sleeve solved coarse to fine and
// directly, both certified.
#include <filesystem>

#include <catch2/catch.hpp>

#include "core/mesh/primitives.hpp"
#include "garment/outfit_meshes.hpp"
#include "retarget/extremes_support.hpp"

using namespace gr;

TEST_CASE("coarse to fine: a dense sleeve follows its proxy onto a capsule, certified",
          "[pipeline][coarse_to_fine]") {
  // 2,304 faces, over twice the proxy's 400: solved coarse to fine, and directly to compare.
  const TriangleMesh sleeve = open_cylinder(0.36, -0.5, 0.5, 25, 48);
  const TriangleMesh body = test::capsule_body(0.31, 1.2);
  RetargetOptions options = test::synthetic_scene("coarse_to_fine", sleeve, body);
  options.overrides.set("proxy_faces", 400);
  const RetargetResult guided = test::run_and_check(options);
  REQUIRE(guided.status == Outcome::kCertified);
  const RetargetReport& r = guided.report;
  REQUIRE(r.proxy.used);
  CHECK(r.proxy.faces >= 300);
  CHECK(r.proxy.faces <= 500);
  CHECK(r.proxy.clearance > 0.0);
  CHECK(r.proxy.inflate_path.points > 0);
  CHECK(r.proxy.inflate_path.points_reached > 0);
  CHECK(r.proxy.fit_path.points > 0);
  // The sleeve follows the proxy's fit to its end, so its own fit only polishes.
  REQUIRE(r.proxy.fit_path.reached_end);
  CHECK(r.fit.newton_iterations <= r.parameters.solver.guided_fit_max_iterations);

  options.overrides.set("proxy_faces", 0);
  options.out_dir = (std::filesystem::path(options.out_dir).parent_path() / "direct").string();
  const RetargetResult direct = test::run_and_check(options);
  REQUIRE(direct.status == Outcome::kCertified);
  CHECK_FALSE(direct.report.proxy.used);
  CHECK_THAT(direct.report.proxy.reason, Catch::Contains("--proxy-faces 0"));
  // The same garment, as close to the body and as little stretched.
  const double guided_fit = r.certify.fit_error.mean;
  const double direct_fit = direct.report.certify.fit_error.mean;
  CAPTURE(guided_fit, direct_fit, r.certify.shape.mean_edge_change,
          direct.report.certify.shape.mean_edge_change);
  CHECK(guided_fit <= 1.5 * direct_fit + 1e-3);
  CHECK(r.certify.shape.mean_edge_change <= direct.report.certify.shape.mean_edge_change + 0.02);
}
