#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "app/cli/commands.hpp"
#include "retarget/scene/shrink_avatar.hpp"
#include "retarget/validate_run.hpp"

namespace gr {

TEST_CASE("typed validate options go through the command's own options and checks",
          "[cli][options][validate]") {
  const nlohmann::json scene = {{"garment", {"inner.obj", "outer.obj"}}, {"avatar", "a.obj"}};
  nlohmann::json keys = scene;
  keys["source"] = {"inner_source.obj", "outer_source.obj"};
  keys["threshold"] = 0.25;
  keys["max-listed"] = 7;
  keys["avatar_mesh"] = "body";
  keys["shape_check"] = "off";
  keys["report"] = "r.json";
  const ValidateOptions options = validate_options_from_json(keys);
  CHECK(options.garments == std::vector<std::string>{"inner.obj", "outer.obj"});
  CHECK(options.avatar == "a.obj");
  CHECK(options.sources == std::vector<std::string>{"inner_source.obj", "outer_source.obj"});
  REQUIRE(options.threshold.has_value());
  CHECK(*options.threshold == 0.25);
  CHECK(options.max_listed == 7);
  CHECK(options.avatar_meshes == std::vector<std::string>{"body"});
  CHECK_FALSE(options.shape_thresholds.enabled);
  CHECK(options.report == "r.json");
  CHECK(options.marks.empty());
  CHECK(validate_options_from_json(scene).max_listed == kDefaultListedIssues);

  const auto refused = [&](const std::string& key, const nlohmann::json& value) {
    nlohmann::json bad = scene;
    bad[key] = value;
    CAPTURE(key, value.dump());
    CHECK_THROWS_AS(validate_options_from_json(bad), CLI::ParseError);
  };
  refused("no_such_option", 1);
  refused("out", "dir");  // retarget's and shrink's, not validate's
  refused("help", true);
  refused("threshold", -1.0);
  refused("threshold", "near");
  refused("max_listed", 2.5);
  refused("report", true);
  refused("shape_check", "maybe");
  CHECK_THROWS_WITH(validate_options_from_json({{"garment", "g.obj"}, {"bogus", 1}}),
                    Catch::Contains("--bogus") && Catch::Contains("validate"));
  CHECK_THROWS_AS(validate_options_from_json({{"garment", "g.obj"}}), CLI::RequiredError);
  CHECK_THROWS_AS(validate_options_from_json(nlohmann::json::array()), CLI::ParseError);
}

TEST_CASE("typed shrink options go through the command's own options and checks",
          "[cli][options][shrink]") {
  const nlohmann::json scene = {{"garment", "g.obj"}, {"avatar", "a.obj"}, {"out", "out"}};
  nlohmann::json keys = scene;
  keys["mode"] = "skeleton";
  keys["voxel_size"] = 0.05;
  keys["source_skeleton"] = "s.obj";
  keys["target-skeleton"] = "t.obj";
  keys["timeout"] = 30;
  keys["quiet"] = true;
  keys["allow_external_assets"] = false;
  const ShrinkRunOptions options = shrink_options_from_json(keys);
  CHECK(options.inputs.garment == "g.obj");
  CHECK(options.inputs.avatar == "a.obj");
  CHECK(options.inputs.source_skeleton == "s.obj");
  CHECK(options.inputs.target_skeleton == "t.obj");
  CHECK(options.out_dir == "out");
  CHECK(options.mode == ShrinkMode::kSkeleton);
  CHECK(options.voxel_size == 0.05);
  CHECK(options.limits.timeout_seconds == 30.0);
  CHECK_FALSE(options.allow_external_assets);
  CHECK(options.quiet);
  const ShrinkRunOptions defaults = shrink_options_from_json(scene);
  CHECK(defaults.mode == ShrinkMode::kLevelset);
  CHECK(defaults.voxel_size == ShrinkRunOptions{}.voxel_size);
  CHECK_FALSE(defaults.quiet);  // progress on stderr

  const auto refused = [&](const std::string& key, const nlohmann::json& value) {
    nlohmann::json bad = scene;
    bad[key] = value;
    CAPTURE(key, value.dump());
    CHECK_THROWS_AS(shrink_options_from_json(bad), CLI::ParseError);
  };
  refused("no_such_option", 1);
  refused("w_fit", 10);  // retarget's knob, not shrink's
  refused("mode", "melt");
  refused("voxel_size", 0);
  refused("voxel_size", "fine");
  refused("quiet", 1);
  CHECK_THROWS_WITH(shrink_options_from_json({{"garment", "g.obj"}, {"quality", "fast"}}),
                    Catch::Contains("--quality") && Catch::Contains("shrink"));
  nlohmann::json missing = scene;
  missing.erase("out");
  CHECK_THROWS_AS(shrink_options_from_json(missing), CLI::RequiredError);
}

}  // namespace gr
