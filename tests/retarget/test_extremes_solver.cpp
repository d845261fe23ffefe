#include <filesystem>
#include <string>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "extremes_support.hpp"
#include "retarget/outcome.hpp"

namespace fs = std::filesystem;
using namespace gr;

TEST_CASE(
    "extremes: a Newton solve capped at one iteration is reported, and the garment "
    "written is still certified",
    "[pipeline][extremes][solver]") {
  const std::string scene = "scenes/dress_form/";
  const fs::path out = test::fresh_temp_dir("extremes_newton_cap");
  const test::CliRun run = test::run_cli(
      {"retarget", "--garment", test::project_file(scene + "garment.obj"), "--avatar",
       test::project_file(scene + "avatar.obj"), "--no-fit",
       test::project_file(scene + "no-fit.txt"), "--out", out.string(), "--quality", "fast",
       "--max-newton-iterations", "1", "--max-al-rounds", "2", "--inflation-step", "0.1"},
      "extremes_newton_cap");
  CAPTURE(run.out, run.err);
  // One Newton step of up to 0.1 already lifts the avatar to a valid snap; the fit's one step is
  // not enough. Every accepted step was CCD-bounded, so the garment is intersection free: it is
  // written and certified, and the cap is reported on stderr and in the report.
  CHECK(run.exit_code == to_exit_code(Outcome::kCertified));
  CHECK_THAT(run.err,
             Catch::Contains("fit stopped before its tolerance: 1 steps without converging") &&
                 Catch::Contains("--max-newton-iterations"));
  REQUIRE(fs::exists(out / "report.json"));
  CHECK(fs::exists(out / "garment.obj"));
  const auto report = nlohmann::json::parse(test::read_text(out / "report.json"));
  CHECK(report["inflate"]["newton_iterations"].get<int>() <= 2);
  CHECK(report["fit"]["status"] == "iteration limit");
  CHECK(report["fit"]["newton_iterations"] == 1);
  CHECK(report["certified"] == true);
  CHECK_FALSE(report["warnings"].empty());
  test::check_outputs_finite(out);
}

TEST_CASE("extremes: a garment 1e-12 from the avatar gives byte-identical files on two runs",
          "[pipeline][extremes][determinism]") {
  std::string written[2];
  for (int run = 0; run < 2; ++run) {
    const RetargetOptions options =
        test::synthetic_scene("determinism_" + std::to_string(run), test::cap_at_gap(1e-12));
    const RetargetResult result = test::run_and_check(options);
    INFO(result.message);
    REQUIRE(result.status == Outcome::kCertified);
    written[run] = test::read_text(result.garment_path);
  }
  CHECK_FALSE(written[0].empty());
  CHECK(written[0] == written[1]);
}
