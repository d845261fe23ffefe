#include <filesystem>
#include <string>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "extremes_support.hpp"
#include "tools/cli/exit_codes.hpp"

namespace fs = std::filesystem;
using namespace gr;

TEST_CASE("extremes: a Newton solve capped at one iteration ends in exit code 4, a report and "
          "no garment",
          "[pipeline][extremes][solver]") {
  const std::string scene = "tools/scenes/dress_form/";
  const fs::path out = test::fresh_temp_dir("extremes_newton_cap");
  const test::CliRun run = test::run_cli(
      {"retarget", "--garment", test::project_file(scene + "garment.obj"), "--avatar",
       test::project_file(scene + "avatar.obj"), "--no-fit", test::project_file(scene + "no-fit.txt"),
       "--out", out.string(), "--quality", "fast", "--max-newton-iterations", "1",
       "--max-al-rounds", "2", "--quiet"},
      "extremes_newton_cap");
  CAPTURE(run.out, run.err);
  CHECK(run.exit_code == kExitSolverFailure);
  CHECK(run.err.empty());
  const auto lines = test::lines_of(run.out);
  REQUIRE(lines.size() == 1);
  // One Newton step already lifts the avatar to a valid snap; the fit's one step is not
  // enough, and a solve stopped by its cap is a failure, not a quietly unfitted garment.
  CHECK_THAT(lines[0], Catch::StartsWith("fit failed: 1 steps without converging") &&
                           Catch::Contains("--max-newton-iterations"));
  REQUIRE(fs::exists(out / "report.json"));
  CHECK_FALSE(fs::exists(out / "garment.obj"));
  CHECK_FALSE(fs::exists(out / "certificate.json"));
  const auto report = nlohmann::json::parse(test::read_text(out / "report.json"));
  CHECK(report["inflate"]["newton_iterations"].get<int>() <= 2);
  CHECK(report["fit"]["status"] == "iteration limit");
  CHECK(report["fit"]["newton_iterations"] == 1);
  CHECK(report["certified"] == false);
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
    REQUIRE(result.status == RetargetStatus::kCertified);
    written[run] = test::read_text(result.garment_path);
  }
  CHECK_FALSE(written[0].empty());
  CHECK(written[0] == written[1]);
}
