// Ease through the program: the skirt on the foxgirl with and without its source body,
// and the bundled scene without one.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "core/io/obj_document.hpp"
#include "retarget/outcome.hpp"
#include "test_support.hpp"

using namespace gr;

namespace {

nlohmann::json read_report(const std::filesystem::path& out) {
  std::ifstream in(out / "report.json");
  return nlohmann::json::parse(in);
}

std::vector<std::string> skirt_on_foxgirl(const std::filesystem::path& out,
                                          const std::vector<std::string>& extra) {
  std::vector<std::string> args = {"retarget",
                                   "--garment",
                                   test::shared_data("garments/skirt/garment.obj"),
                                   "--avatar",
                                   test::shared_data("avatars/foxgirl/avatar.obj"),
                                   "--source-skeleton",
                                   test::shared_data("garments/skirt/skeleton.obj"),
                                   "--target-skeleton",
                                   test::shared_data("avatars/foxgirl/skeleton.obj"),
                                   "--no-fit",
                                   test::shared_data("garments/skirt/no-fit.txt"),
                                   "--skirt",
                                   "--source-body",
                                   test::shared_data("garments/skirt/source_body.obj"),
                                   "--quality",
                                   "fast",
                                   "--quiet",
                                   "--out",
                                   out.string()};
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

}  // namespace

TEST_CASE("With its source body the skirt keeps its ease - the tight fit paints it on",
          "[ease][cli][shared]") {
  const std::filesystem::path root = test::fresh_temp_dir("ease_skirt");
  const test::CliRun ease = test::run_cli(skirt_on_foxgirl(root / "ease", {}), "ease_skirt");
  CAPTURE(ease.err);
  REQUIRE(ease.exit_code == to_exit_code(Outcome::kCertified));
  const nlohmann::json kept = read_report(root / "ease")["ease"];
  CAPTURE(kept.dump());
  CHECK(kept["fit"] == "ease");
  CHECK(kept["measured_vertices"].get<int>() > 500);
  CHECK(kept["median_ratio"].get<double>() == Approx(1.0).margin(0.25));
  CHECK(kept["within_25_percent"].get<double>() >= 0.5);
  CHECK(static_cast<Eigen::Index>(kept["per_vertex_ratio"].size()) ==
        read_obj(test::shared_data("garments/skirt/garment.obj")).positions.rows());

  const test::CliRun tight =
      test::run_cli(skirt_on_foxgirl(root / "tight", {"--fit", "tight"}), "tight_skirt");
  REQUIRE(tight.exit_code == to_exit_code(Outcome::kCertified));
  const nlohmann::json painted = read_report(root / "tight")["ease"];
  CHECK(painted["fit"] == "tight");
  CHECK(painted["median_ratio"].get<double>() < 0.4);
  CHECK(painted["within_25_percent"].get<double>() < 0.1);
}

TEST_CASE("Without a source body the fit is tight, with a warning - ease asks for one",
          "[ease][cli]") {
  const std::filesystem::path root = test::fresh_temp_dir("ease_bundled");
  const std::string scene = test::project_file("scenes/dress_form/");
  std::vector<std::string> args = {"retarget",
                                   "--garment",
                                   scene + "garment.obj",
                                   "--avatar",
                                   scene + "avatar.obj",
                                   "--no-fit",
                                   scene + "no-fit.txt",
                                   "--quality",
                                   "fast",
                                   "--quiet",
                                   "--out",
                                   (root / "tight").string()};
  REQUIRE(test::run_cli(args, "ease_bundled").exit_code == to_exit_code(Outcome::kCertified));
  const nlohmann::json report = read_report(root / "tight");
  CHECK(report["ease"]["fit"] == "tight");
  CHECK(report["ease"]["source"] == "none");
  CHECK_THAT(report["warnings"].dump(), Catch::Contains("no --source-body"));

  args.back() = (root / "ease").string();
  args.insert(args.end(), {"--fit", "ease"});
  const test::CliRun refused = test::run_cli(args, "ease_refused");
  CHECK(refused.exit_code == to_exit_code(Outcome::kBadInput));
  CHECK_THAT(refused.err, Catch::Contains("--fit ease needs the garment's source body"));
}
