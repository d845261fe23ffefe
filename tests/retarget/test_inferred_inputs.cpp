// Rigged assets as users have them: the shared pairings without skin weights (bound from the
// skeleton) and without a hand-made no-fit list (inferred). Reads ../shared/data.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "core/io/rig_files.hpp"
#include "normalized_shared_scene.hpp"
#include "retarget/outcome.hpp"
#include "shrink/binding/voxel_binding.hpp"
#include "shrink/shrink_oracles.hpp"
#include "shrink/shrunk_avatar/shrink_certification.hpp"
#include "shrink/shrunk_avatar/skeleton_shrink.hpp"

using namespace gr;
namespace fs = std::filesystem;

namespace {

/// `retarget` of the shared puffer onto the goblin with both skeletons, then `more`.
std::vector<std::string> puffer_on_goblin(const std::vector<std::string>& more) {
  const std::string d = test::shared_data("");
  std::vector<std::string> args = {"retarget",
                                   "--garment",
                                   d + "/garments/puffer/garment.obj",
                                   "--avatar",
                                   d + "/avatars/goblin/avatar.obj",
                                   "--source-skeleton",
                                   d + "/garments/puffer/skeleton.obj",
                                   "--target-skeleton",
                                   d + "/avatars/goblin/skeleton.obj"};
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

}  // namespace

TEST_CASE("skeleton shrink of every shared pairing with bound weights is certified",
          "[shrink][skeleton][binding]") {
  const auto [garment, avatar] = GENERATE(table<std::string, std::string>(
      {{"skirt", "foxgirl"}, {"puffer", "goblin"}, {"skirt", "goblin"}, {"puffer", "foxgirl"}}));
  CAPTURE(garment, avatar);
  const test::NormalizedScene scene = test::load_normalized_scene(garment, avatar);
  const Binding binding = bind_skeleton(scene.avatar, scene.target_skeleton);
  const ShrinkResult result = shrink_to_skeleton(scene.avatar, scene.garment, scene.source_skeleton,
                                                 scene.target_skeleton, binding.weights);
  test::require_certified(scene.avatar, result, scene.garment);
  if (garment == "puffer" && avatar == "goblin") {
    // Without weights the nearest bone sends thigh vertices to a forearm; pulled along the
    // bones toward the joints where their faces' bones meet, even a pullback of 0.05 clears
    // the garment (pulled straight, no shrink was found from there).
    SkeletonShrinkOptions thin;
    thin.pullback = 0.05;
    thin.max_halvings = 6;
    const ShrinkResult nearest =
        shrink_to_skeleton(scene.avatar, scene.garment, scene.source_skeleton,
                           scene.target_skeleton, Eigen::MatrixXd(), thin);
    test::require_certified(scene.avatar, nearest, scene.garment);
    CHECK(nearest.collapsed_vertices > 0);
  }
}

TEST_CASE("retarget infers the skin weights and the no-fit list it is not given",
          "[pipeline][e2e][inference]") {
  const std::string d = test::shared_data("");
  const fs::path out = test::fresh_temp_dir("inferred_inputs");
  const test::CliRun run =
      test::run_cli(puffer_on_goblin({"--source-body", d + "/garments/puffer/source_body.obj",
                                      "--quality", "fast", "--out", out.string(), "--quiet"}),
                    "inferred_inputs");
  CAPTURE(run.out, run.err);
  REQUIRE(run.exit_code == 0);

  std::ifstream report_file(out / "report.json");
  const nlohmann::json report = nlohmann::json::parse(report_file);
  REQUIRE(report["certified"] == true);
  const nlohmann::json& inferred = report["inferred"];
  REQUIRE(inferred["skin_weights"]["inferred"] == true);
  REQUIRE(inferred["skin_weights"]["method"] == "geodesic");
  REQUIRE(inferred["skin_weights"]["binding"]["vertices_through_interior"].get<int>() > 0);
  REQUIRE(inferred["no_fit"]["inferred"] == true);
  REQUIRE(inferred["no_fit"]["method"] == "source body distance");
  REQUIRE(inferred["no_fit"]["free_faces"].get<int>() > 0);
  REQUIRE(report["modelled"]["fit_faces"].get<int>() +
              inferred["no_fit"]["free_faces"].get<int>() ==
          report["modelled"]["garment_faces"].get<int>());

  // DIR/no-fit.txt is a list the command reads back: 0-based OBJ vertex ids.
  const std::string list = (out / "no-fit.txt").string();
  REQUIRE(inferred["no_fit"]["path"] == list);
  const std::vector<int> ids = read_vertex_list(list, 1 << 20);
  REQUIRE(ids.size() >= inferred["no_fit"]["vertices"].get<std::size_t>());
}

TEST_CASE("an inflation that stalls from a thick shrunk avatar runs again from a thinner one",
          "[pipeline][e2e][skeleton]") {
  // At pullback 0.5 the goblin's arms and body grow into the puffer between them: t stalls
  // near 0.58. A fifth of the pullback leaves the puffer room.
  const std::string d = test::shared_data("");
  const fs::path out = test::fresh_temp_dir("thinned_shrink");
  const test::CliRun run = test::run_cli(
      puffer_on_goblin({"--no-fit", d + "/garments/puffer/no-fit.txt", "--skin-weights",
                        d + "/avatars/goblin/skin.txt", "--pullback", "0.5", "--quality", "fast",
                        "--out", out.string()}),
      "thinned_shrink");
  CAPTURE(run.out, run.err);
  REQUIRE(run.exit_code == 0);
  CHECK(run.err.find("inflate  stalled at t = ") != std::string::npos);
  CHECK(run.err.find("shrinking the avatar again with pullback 0.1") != std::string::npos);

  std::ifstream report_file(out / "report.json");
  const nlohmann::json report = nlohmann::json::parse(report_file);
  CHECK(report["certified"] == true);
  CHECK(report["shrink"]["thinned"] == true);
  CHECK(report["shrink"]["pullback"].get<double>() == Approx(0.1));
  CHECK(report["parameters"]["skeleton_pullback"].get<double>() == 0.5);
  CHECK(report["inflate"]["status"] == "snapped");
}

TEST_CASE("an inflation that fails from a shrink and from a thinner one is a solver failure",
          "[pipeline][e2e][skeleton]") {
  // Bound to the nearest bones, the goblin's thighs start on a forearm: the shrink at 0.25
  // is free of the puffer, but two rounds cannot carry them home; the run shrinks again
  // thinner, inflates once more, and ends with the inflation's failure.
  const std::string d = test::shared_data("");
  const fs::path out = test::fresh_temp_dir("thinner_shrink_fails");
  const test::CliRun run =
      test::run_cli(puffer_on_goblin({"--no-fit", d + "/garments/puffer/no-fit.txt", "--binding",
                                      "nearest", "--max-al-rounds", "2", "--quality", "fast",
                                      "--out", out.string(), "--quiet"}),
                    "thinner_shrink_fails");
  CAPTURE(run.out, run.err);
  CHECK(run.exit_code == gr::to_exit_code(gr::Outcome::kSolverFailure));
  CHECK_THAT(run.out, Catch::Contains("inflation failed"));
  const auto report = nlohmann::json::parse(test::read_text(out / "report.json"));
  CHECK(report["shrink"]["thinned"] == true);
  CHECK_FALSE(fs::exists(out / "garment.obj"));
}

TEST_CASE("a root joint outside the skeleton is bad input", "[pipeline][inference]") {
  const std::string d = test::shared_data("");
  const fs::path out = test::fresh_temp_dir("inferred_root");
  const test::CliRun run = test::run_cli(
      {"retarget", "--garment", d + "/garments/skirt/garment.obj", "--avatar",
       d + "/avatars/foxgirl/avatar.obj", "--source-skeleton", d + "/garments/skirt/skeleton.obj",
       "--target-skeleton", d + "/avatars/foxgirl/skeleton.obj", "--root-joint", "15", "--out",
       out.string(), "--quiet"},
      "inferred_root");
  CAPTURE(run.out, run.err);
  REQUIRE(run.exit_code == 2);
  REQUIRE_THAT(run.err, Catch::Contains("root joint 15 is not a joint of the skeletons (0 to 14)"));
}
