#include <fstream>
#include <string>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "report_page/page_test_support.hpp"
#include "scenes/synthetic/bending_arm.hpp"
#include "test_support.hpp"

namespace gr {
namespace {

nlohmann::json read_json(const std::filesystem::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

/// The arm scene, its elbow bending by `degrees`, written into a fresh folder.
std::filesystem::path arm_scene(const std::string& name, double degrees = 90.0) {
  const auto dir = test::fresh_temp_dir(name);
  write_bending_arm_scene(make_bending_arm_scene(degrees), dir.string());
  return dir;
}

TEST_CASE("validate --animation finds the frames where a skinned sleeve crosses its bending arm",
          "[validate][animation]") {
  const auto dir = arm_scene("validate_animation_bend");
  const test::CliRun run = test::run_cli({"validate", "--garment", (dir / "sleeve.glb").string(),
                                          "--avatar", (dir / "arm.glb").string(), "--animation",
                                          "bend", "--report", (dir / "report.json").string()},
                                         "validate_animation_bend");
  INFO(run.out << run.err);
  CHECK(run.exit_code == 1);
  CHECK_THAT(run.out, Catch::Contains("animation 'bend': 31 frames at 30 fps"));
  CHECK_THAT(run.out, Catch::StartsWith("NOT certified (frames of an animation cross)"));
  const nlohmann::json report = read_json(dir / "report.json");
  // The sleeve is certified as written: only the played frames cross.
  CHECK(report["counts"]["garment_avatar_intersections"] == 0);
  CHECK(report["certified"] == false);
  const nlohmann::json& clip = report["animations"].at(0);
  CHECK(clip["clip"] == "bend");
  CHECK(clip["translations"] == "all");
  CHECK(clip["frame_count"] == 31);
  CHECK(clip["avatar_driven_joints"] == 1);
  const nlohmann::json& frames = clip["frames"];
  CHECK(frames.at(0)["avatar_pairs"] == 0);
  CHECK(frames.at(0)["self_pairs"] == 0);
  CHECK(frames.at(30)["avatar_pairs"].get<int>() > 0);
  const int first = clip["first_crossing_frame"]["index"];
  CHECK(first > 0);
  CHECK(clip["crossing_frames"].get<int>() == 31 - first);
  CHECK(clip["worst_frame"]["pairs"].get<int>() >= frames.at(first)["avatar_pairs"].get<int>());
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST_CASE("validate --animation --html puts the clip's frames on the page's slider",
          "[validate][animation]") {
  const auto dir = arm_scene("validate_animation_page");
  const test::CliRun run =
      test::run_cli({"validate", "--garment", (dir / "sleeve.glb").string(), "--avatar",
                     (dir / "arm.glb").string(), "--animation", "bend", "--report",
                     (dir / "report.json").string(), "--html", (dir / "page.html").string()},
                    "validate_animation_page");
  INFO(run.out << run.err);
  CHECK(run.exit_code == 1);
  const nlohmann::json clip = read_json(dir / "report.json")["animations"].at(0);
  const std::string html = read_text(dir / "page.html");
  const nlohmann::json page = test::scene_of(html)["animation"];
  CHECK(page["clip"] == "bend");
  CHECK(page["fps"] == 30.0);
  CHECK(page["clip_count"] == 1);
  CHECK(page["frame_count"] == clip["frame_count"]);
  CHECK(page["first_crossing"] == clip["first_crossing_frame"]["index"]);
  CHECK(page["worst_frame"] == clip["worst_frame"]["index"]);
  const nlohmann::json& frames = clip["frames"];
  REQUIRE(page["times"].size() == frames.size());
  for (std::size_t f = 0; f < frames.size(); ++f) {
    CAPTURE(f);
    CHECK(page["times"][f] == frames[f]["time"]);
    CHECK(page["avatar_pairs"][f] == frames[f]["avatar_pairs"]);
    CHECK(page["self_pairs"][f] == frames[f]["self_pairs"]);
    CHECK(page["layer_pairs"][f] == frames[f]["layer_pairs"]);
    const bool crossing =
        frames[f]["avatar_pairs"].get<int>() + frames[f]["self_pairs"].get<int>() > 0;
    CHECK(page["garments"][0]["marked"][f].empty() == !crossing);
  }
  CHECK(test::between(html, "id=\"gr-mark-worst\" data-frame=\"", "\"") ==
        std::to_string(clip["worst_frame"]["index"].get<int>()));
  // The avatar and the sleeve in every frame.
  CHECK(page["avatar"]["frames"].size() == frames.size());
}

TEST_CASE("the dress's validation page through the idle clip stays under 20 MB",
          "[validate][animation]") {
  const auto dir = test::fresh_temp_dir("validate_animation_dress_page");
  const test::CliRun run = test::run_cli(
      {"validate", "--garment", test::shared_data("real/female-pose-standing.glb"),
       "--garment-mesh", "Wolf3D_Outfit_Top.002", "--avatar",
       test::shared_data("real/female-full-body.glb"), "--avatar-mesh", "body.001", "--animation",
       test::shared_data("real/female-idle.glb"), "--html", (dir / "page.html").string()},
      "validate_animation_dress_page");
  INFO(run.out << run.err);
  CHECK(run.exit_code == 1);
  CHECK_THAT(run.out, Catch::Contains("252 frames at 30 fps"));
  const auto size = std::filesystem::file_size(dir / "page.html");
  CAPTURE(size);
  CHECK(size < 20'000'000);
  const nlohmann::json page = test::scene_of(read_text(dir / "page.html"))["animation"];
  CHECK(page["frame_count"] == 252);
  CHECK(page["avatar"]["frames"].size() == 252);
}

TEST_CASE("a clip from another file drives the joints of the same names", "[validate][animation]") {
  const auto dir = arm_scene("validate_animation_other_file");
  const auto report_of = [&](const std::string& spec, const std::string& name) {
    const test::CliRun run = test::run_cli({"validate", "--garment", (dir / "sleeve.glb").string(),
                                            "--avatar", (dir / "arm.glb").string(), "--animation",
                                            spec, "--report", (dir / (name + ".json")).string()},
                                           name);
    INFO(run.out << run.err);
    CHECK(run.exit_code == 1);
    return read_json(dir / (name + ".json"))["animations"].at(0);
  };
  const nlohmann::json own = report_of("bend", "own");
  const nlohmann::json other = report_of((dir / "clip.glb").string() + "#bend", "other");
  CHECK(other["translations"] == "roots");
  CHECK(other["file"] == (dir / "clip.glb").string());
  CHECK(other["crossing_frames"] == own["crossing_frames"]);
  CHECK(other["frames"] == own["frames"]);
  // A whole file's clips, by the file alone.
  CHECK(report_of((dir / "clip.glb").string(), "whole_file")["frames"] == own["frames"]);
}

TEST_CASE("validate --animation refuses a clip it cannot find and an unskinned garment",
          "[validate][animation]") {
  const auto dir = arm_scene("validate_animation_refusals");
  const test::CliRun unknown =
      test::run_cli({"validate", "--garment", (dir / "sleeve.glb").string(), "--avatar",
                     (dir / "arm.glb").string(), "--animation", "wave"},
                    "validate_animation_unknown");
  CHECK(unknown.exit_code == 2);
  CHECK_THAT(unknown.err,
             Catch::Contains("no animation named 'wave'") && Catch::Contains("'bend'"));
  CHECK(test::lines_of(unknown.err).size() == 1);

  std::ofstream(dir / "sleeve.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const test::CliRun unskinned =
      test::run_cli({"validate", "--garment", (dir / "sleeve.obj").string(), "--avatar",
                     (dir / "arm.glb").string(), "--animation", "bend"},
                    "validate_animation_unskinned");
  CHECK(unskinned.exit_code == 2);
  CHECK_THAT(unskinned.err, Catch::Contains("sleeve.obj") && Catch::Contains("skin"));

  // A rate that would sample the 1 s clip in a billion frames is refused before any frame
  // is posed, by validate and by retarget, which then writes nothing.
  const test::CliRun too_fast =
      test::run_cli({"validate", "--garment", (dir / "sleeve.glb").string(), "--avatar",
                     (dir / "arm.glb").string(), "--animation", "bend", "--fps", "1e9"},
                    "validate_animation_too_fast");
  CHECK(too_fast.exit_code == 2);
  CHECK_THAT(too_fast.err, Catch::Contains("'bend'") && Catch::Contains("lower --fps"));
  CHECK(test::lines_of(too_fast.err).size() == 1);
  const auto out = dir / "too-fast";
  const test::CliRun retarget_too_fast = test::run_cli(
      {"retarget", "--garment", (dir / "sleeve.glb").string(), "--avatar",
       (dir / "arm.glb").string(), "--animation", "bend", "--fps", "1e9", "--out", out.string()},
      "retarget_animation_too_fast");
  CHECK(retarget_too_fast.exit_code == 2);
  CHECK_THAT(retarget_too_fast.err, Catch::Contains("lower --fps"));
  CHECK_FALSE(std::filesystem::exists(out));
}

TEST_CASE("retarget --animation writes a sleeve certified in every frame, and validate agrees",
          "[retarget][animation]") {
  // The sleeve was made on this arm: given as its source body, the fit keeps its ease, which
  // leaves the cloth room in the crease of the bent elbow.
  const auto dir = arm_scene("retarget_animation_bend", 45.0);
  const auto out = dir / "out";
  const test::CliRun run =
      test::run_cli({"retarget", "--garment", (dir / "sleeve.glb").string(), "--avatar",
                     (dir / "arm.glb").string(), "--source-body", (dir / "arm.glb").string(),
                     "--animation", "bend", "--out", out.string(), "--quiet"},
                    "retarget_animation_bend");
  INFO(run.out << run.err);
  REQUIRE(run.exit_code == 0);
  CHECK_THAT(run.out, Catch::Contains("animation 'bend': 31 frames at 30 fps, 0 crossing"));
  const nlohmann::json report = read_json(out / "report.json");
  const nlohmann::json& clip = report["animation"]["clips"].at(0);
  CHECK(report["animation"]["certified"] == true);
  CHECK(clip["written"]["crossing_frames"] == 0);
  CHECK(clip["skinning_alone"]["crossing_frames"].get<int>() > 0);
  CHECK(clip["corrected_frames"].get<int>() ==
        clip["skinning_alone"]["crossing_frames"].get<int>());
  CHECK(clip["seconds_per_frame"].get<double>() > 0.0);
  // The page plays the written file through the clip: every frame free.
  const nlohmann::json page = test::scene_of(read_text(out / "report.html"))["animation"];
  CHECK(page["clip"] == "bend");
  CHECK(page["frame_count"] == 31);
  CHECK(page["worst_frame"].is_null());
  CHECK(page["first_crossing"].is_null());
  for (std::size_t f = 0; f < 31; ++f)
    CHECK(page["avatar_pairs"][f].get<int>() + page["self_pairs"][f].get<int>() == 0);

  // The written file played on its own, by the validator, with the clip of the arm's file.
  const test::CliRun check =
      test::run_cli({"validate", "--garment", (out / "garment.glb").string(), "--avatar",
                     (dir / "arm.glb").string(), "--animation", "bend"},
                    "retarget_animation_validate");
  INFO(check.out << check.err);
  CHECK(check.exit_code == 0);
  CHECK_THAT(check.out, Catch::Contains("31 frames at 30 fps, 0 crossing"));
}

TEST_CASE("retarget --animation is refused up front without a skinned output",
          "[retarget][animation]") {
  const auto dir = arm_scene("retarget_animation_obj");
  const test::CliRun run =
      test::run_cli({"retarget", "--garment", (dir / "sleeve.glb").string(), "--avatar",
                     (dir / "arm.glb").string(), "--animation", "bend", "--format", "obj", "--out",
                     (dir / "out").string(), "--quiet"},
                    "retarget_animation_obj");
  CHECK(run.exit_code == 2);
  CHECK_THAT(run.err, Catch::Contains("--animation needs"));
  CHECK_FALSE(std::filesystem::exists(dir / "out"));
}

}  // namespace
}  // namespace gr
