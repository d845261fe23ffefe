#include <cmath>
#include <string>

#include <fmt/format.h>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "extremes_support.hpp"

using namespace gr;

namespace {

/// The reference dhat of the presets (normalized units).
constexpr double kDefaultDhat = 0.002;

nlohmann::json read_report(const RetargetResult& result) {
  return nlohmann::json::parse(test::read_text(result.report_path));
}

}  // namespace

TEST_CASE("extremes: a garment starting a hair's breadth outside the avatar is certified",
          "[pipeline][extremes][gap]") {
  const double gap = GENERATE(1e-12, 1e-9, 0.5 * kDefaultDhat);
  CAPTURE(gap);
  const RetargetResult result = test::run_and_check(
      test::synthetic_scene(fmt::format("gap_{:g}", gap), test::cap_at_gap(gap)));
  INFO(result.message);
  REQUIRE(result.status == Outcome::kCertified);
  const nlohmann::json report = read_report(result);
  CHECK(report["min_distance"]["normalized"].get<double>() > 0.0);
}

TEST_CASE("extremes: barrier support dhat from 1e-5 to 1e-1", "[pipeline][extremes][parameters]") {
  const double dhat = GENERATE(1e-5, 1e-4, 1e-3, 1e-2, 1e-1);
  CAPTURE(dhat);
  RetargetOptions options =
      test::synthetic_scene(fmt::format("dhat_{:g}", dhat), test::cap_inside());
  options.overrides.set("dhat", dhat);
  options.overrides.set("max_al_rounds", 4);
  // The thinnest barrier never converges (below); fewer steps keep its failure quick.
  if (dhat < 1e-4) options.overrides.set("max_newton_iterations", 100);
  // At 1e-4 the proximal tether (w_tether) slows the push on t: it needs more rounds.
  if (dhat == 1e-4) options.overrides.set("max_al_rounds", 8);
  const RetargetResult result = test::run_and_check(options);
  INFO(result.message);
  if (dhat < 1e-4 && result.status == Outcome::kSolverFailure) {
    // A barrier this thin acts only within 1e-5 of the avatar and every CCD-bounded step
    // keeps a tenth of each gap, so t crawls: the run stops as stalled (or at the round
    // cap) and says which knobs to turn.
    CHECK_THAT(result.message,
               (Catch::Contains("stalled at t = ") || Catch::Contains("no collision-free snap")) &&
                   Catch::Contains("--dhat"));
    return;
  }
  REQUIRE(result.status == Outcome::kCertified);
  const nlohmann::json report = read_report(result);
  // The solver's avatar is rounded to the lattice: no pair comes within the rounding.
  const double lattice = report["parameters"]["lattice"].get<double>();
  // A distance between points of coordinates near 1 carries a few 1e-16 of rounding: a
  // pair stopped by the CCD exactly at its separation may read that much below it.
  CHECK(report["min_distance"]["normalized"].get<double>() >= std::sqrt(3.0) * lattice - 1e-15);
}

TEST_CASE("extremes: barrier stiffness from 1e4 to 1e12", "[pipeline][extremes][parameters]") {
  const double stiffness = GENERATE(1e4, 1e6, 1e8, 1e10, 1e12);
  CAPTURE(stiffness);
  RetargetOptions options =
      test::synthetic_scene(fmt::format("stiffness_{:g}", stiffness), test::cap_inside());
  options.overrides.set("w_contact", stiffness);
  const RetargetResult result = test::run_and_check(options);
  INFO(result.message);
  // So stiff a barrier dwarfs the fit term that from 1e10 the fit creeps to its cap: the
  // garment is still certified, and the report says the fit stopped early.
  REQUIRE(result.status == Outcome::kCertified);
  if (result.report.fit.status != "converged") {
    REQUIRE_FALSE(result.report.warnings.empty());
    CHECK_THAT(result.report.warnings.back(), Catch::Contains("--max-newton-iterations"));
  }
}

TEST_CASE("extremes: Newton tolerance eps_tol from 1e-2 to 1e-10",
          "[pipeline][extremes][parameters]") {
  const double eps_tol = GENERATE(1e-2, 1e-4, 1e-6, 1e-8, 1e-10);
  CAPTURE(eps_tol);
  RetargetOptions options =
      test::synthetic_scene(fmt::format("eps_{:g}", eps_tol), test::cap_inside());
  options.overrides.set("eps_tol", eps_tol);
  const RetargetResult result = test::run_and_check(options);
  INFO(result.message);
  REQUIRE(result.status == Outcome::kCertified);
}
