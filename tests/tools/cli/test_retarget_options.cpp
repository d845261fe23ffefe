#include <string>

#include <catch2/catch.hpp>

#include "tools/cli/commands.hpp"
#include "tools/pipeline/retarget.hpp"

namespace gr {

namespace {

nlohmann::json scene_keys() { return {{"garment", "g.obj"}, {"avatar", "a.obj"}, {"out", "out"}}; }

}  // namespace

TEST_CASE("typed retarget options go through the command's own options and checks",
          "[cli][options]") {
  nlohmann::json keys = scene_keys();
  keys["quality"] = "fast";
  keys["source_skeleton"] = "s.obj";
  keys["target-skeleton"] = "t.obj";
  keys["skirt"] = true;
  keys["frames"] = false;
  keys["w_fit"] = 10;
  keys["fit_samples"] = 6;
  keys["no_self_contact"] = true;
  keys["avatar_mesh"] = nlohmann::json::array({"body", "head"});
  keys["timeout"] = 30;
  keys["shrink"] = "skeleton";
  keys["fit"] = "tight";
  const RetargetOptions options = retarget_options_from_json(keys);
  CHECK(options.inputs.garment == "g.obj");
  CHECK(options.inputs.source_skeleton == "s.obj");
  CHECK(options.inputs.target_skeleton == "t.obj");
  CHECK(options.out_dir == "out");
  CHECK(options.quality == Quality::kFast);
  CHECK(options.skirt);
  CHECK_FALSE(options.frames);
  CHECK(options.overrides.get("w_fit") == 10.0);
  CHECK(options.overrides.get("fit_samples_per_face") == 6.0);
  CHECK(options.overrides.get("self_contact") == 0.0);
  CHECK(options.inputs.avatar_meshes == std::vector<std::string>{"body", "head"});
  CHECK(options.limits.timeout_seconds == 30.0);
  CHECK(options.shrink_mode == ShrinkMode::kSkeleton);
  CHECK(options.fit_mode == FitMode::kTight);

  const auto refused = [](const std::string& key, const nlohmann::json& value) {
    nlohmann::json bad = scene_keys();
    bad[key] = value;
    CAPTURE(key, value.dump());
    CHECK_THROWS_AS(retarget_options_from_json(bad), CLI::ParseError);
  };
  refused("no_such_option", 1);
  refused("help", true);
  refused("skirt", 1);             // a flag takes a boolean
  refused("quality", "best");      // not a preset
  refused("fit_samples", 4);       // the knob's range
  refused("max_al_rounds", 2.5);   // a count
  refused("dhat", "thin");         // not a number
  refused("dhat", true);           // a boolean for a value
  refused("skin_max_angle", 200);  // the option's own range
  nlohmann::json missing = scene_keys();
  missing.erase("out");
  CHECK_THROWS_AS(retarget_options_from_json(missing), CLI::RequiredError);
  CHECK_THROWS_AS(retarget_options_from_json(nlohmann::json::array()), CLI::ParseError);
}

}  // namespace gr
