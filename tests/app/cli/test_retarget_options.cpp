#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "app/cli/commands.hpp"
#include "cli_runner.hpp"
#include "core/io/formats/mesh_formats.hpp"
#include "retarget/retarget.hpp"

namespace gr {

namespace {

nlohmann::json scene_keys() { return {{"garment", "g.obj"}, {"avatar", "a.obj"}, {"out", "out"}}; }

/// The message distribute_garments refuses `lists` with; empty when it accepts them.
std::string refusal(const GarmentLists& lists) {
  ScenePaths inputs;
  try {
    distribute_garments(lists, inputs);
  } catch (const CLI::ValidationError& e) {
    return e.what();
  }
  return "";
}

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

TEST_CASE("one garment file with several meshes gives a layer per mesh", "[cli][options][outfit]") {
  GarmentLists lists;
  lists.garments = {"outfit.glb"};
  lists.garment_meshes = {"Shirt", "Trousers", "Coat"};
  ScenePaths inputs;
  distribute_garments(lists, inputs);
  CHECK(inputs.garment == "outfit.glb");
  CHECK(inputs.garment_mesh == "Shirt");
  REQUIRE(inputs.more_garments.size() == 2);
  CHECK(inputs.more_garments[0].garment == "outfit.glb");
  CHECK(inputs.more_garments[0].garment_mesh == "Trousers");
  CHECK(inputs.more_garments[1].garment == "outfit.glb");
  CHECK(inputs.more_garments[1].garment_mesh == "Coat");

  // One mesh of one file is one garment, not an outfit.
  lists.garment_meshes = {"Shirt"};
  distribute_garments(lists, inputs);
  CHECK(inputs.garment_mesh == "Shirt");
  CHECK(inputs.more_garments.empty());
}

TEST_CASE("garment files pair with their meshes and their own files in order",
          "[cli][options][outfit]") {
  GarmentLists lists;
  lists.garments = {"shirt.glb", "trousers.glb"};
  lists.garment_meshes = {"Shirt", "Legs"};
  lists.no_fits = {"shirt.txt", "trousers.txt"};
  lists.source_skeletons = {"s1.obj", "s2.obj"};
  lists.source_bodies = {"b1.obj", "b2.obj"};
  ScenePaths inputs;
  distribute_garments(lists, inputs);
  CHECK(inputs.garment == "shirt.glb");
  CHECK(inputs.garment_mesh == "Shirt");
  CHECK(inputs.no_fit == "shirt.txt");
  CHECK(inputs.source_skeleton == "s1.obj");
  CHECK(inputs.source_body == "b1.obj");
  REQUIRE(inputs.more_garments.size() == 1);
  const GarmentPaths& second = inputs.more_garments[0];
  CHECK(second.garment == "trousers.glb");
  CHECK(second.garment_mesh == "Legs");
  CHECK(second.no_fit == "trousers.txt");
  CHECK(second.source_skeleton == "s2.obj");
  CHECK(second.source_body == "b2.obj");

  // Once for all: the first garment's, and the others are in its frame, on its body.
  lists.garment_meshes.clear();
  lists.no_fits.clear();
  lists.source_skeletons = {"s.obj"};
  lists.source_bodies = {"body.obj"};
  distribute_garments(lists, inputs);
  CHECK(inputs.garment_mesh.empty());
  CHECK(inputs.source_skeleton == "s.obj");
  CHECK(inputs.source_body == "body.obj");
  REQUIRE(inputs.more_garments.size() == 1);
  CHECK(inputs.more_garments[0].garment == "trousers.glb");
  CHECK(inputs.more_garments[0].source_skeleton.empty());
  CHECK(inputs.more_garments[0].source_body.empty());
  CHECK(inputs.more_garments[0].no_fit.empty());
}

TEST_CASE("per-garment options given the wrong number of times are refused by name",
          "[cli][options][outfit]") {
  GarmentLists two;
  two.garments = {"a.obj", "b.obj"};

  GarmentLists lists = two;
  lists.garment_meshes = {"A", "B", "C"};
  CHECK_THAT(refusal(lists), Catch::StartsWith("--garment-mesh") &&
                                 Catch::Contains("given 3 times for 2 garment files"));
  lists.garment_meshes = {"A"};  // several files: one each or none
  CHECK_THAT(refusal(lists), Catch::StartsWith("--garment-mesh"));

  lists = two;
  lists.no_fits = {"a.txt"};  // no list is shared
  CHECK_THAT(refusal(lists), Catch::StartsWith("--no-fit") &&
                                 Catch::Contains("given 1 times for 2 garments") &&
                                 !Catch::Contains("once for all"));
  lists.no_fits = {"a.txt", "b.txt", "c.txt"};
  CHECK_THAT(refusal(lists), Catch::StartsWith("--no-fit"));

  lists = two;
  lists.garments.push_back("c.obj");
  lists.source_skeletons = {"s1.obj", "s2.obj"};
  CHECK_THAT(refusal(lists), Catch::StartsWith("--source-skeleton") &&
                                 Catch::Contains("once for all, or once per garment"));
  lists.source_skeletons.clear();
  lists.source_bodies = {"b1.obj", "b2.obj"};
  CHECK_THAT(refusal(lists), Catch::StartsWith("--source-body"));

  // A file with three meshes is three garments: two no-fit lists are one too few.
  lists = GarmentLists{};
  lists.garments = {"outfit.glb"};
  lists.garment_meshes = {"A", "B", "C"};
  lists.no_fits = {"a.txt", "b.txt"};
  CHECK_THAT(refusal(lists), Catch::StartsWith("--no-fit") && Catch::Contains("for 3 garments"));

  CHECK_THAT(refusal(GarmentLists{}), Catch::StartsWith("--garment"));

  lists = two;
  lists.source_bodies = {"body.obj"};
  lists.source_skeletons = {"s.obj"};
  lists.no_fits = {"a.txt", "b.txt"};
  CHECK(refusal(lists).empty());
}

TEST_CASE("the command line refuses a garment mesh count that does not match, before reading",
          "[cli][options][outfit]") {
  const std::filesystem::path dir = test::fresh_temp_dir("outfit_mesh_count");
  const test::CliRun run =
      test::run_cli({"retarget", "--garment", "a.glb", "--garment", "b.glb", "--garment-mesh", "A",
                     "--garment-mesh", "B", "--garment-mesh", "C", "--avatar", "avatar.glb",
                     "--out", (dir / "out").string()},
                    "outfit_mesh_count");
  CHECK(run.exit_code == 2);
  CHECK_THAT(run.err, Catch::Contains("--garment-mesh") &&
                          Catch::Contains("given 3 times for 2 garment files"));
  CHECK_FALSE(std::filesystem::exists(dir / "out"));

  const test::CliRun no_fit =
      test::run_cli({"retarget", "--garment", "a.obj", "--garment", "b.obj", "--no-fit", "a.txt",
                     "--avatar", "avatar.obj", "--out", (dir / "out").string()},
                    "outfit_no_fit_count");
  CHECK(no_fit.exit_code == 2);
  CHECK_THAT(no_fit.err,
             Catch::Contains("--no-fit") && Catch::Contains("given 1 times for 2 garments"));
}

TEST_CASE("typed retarget options take an outfit's garments as arrays", "[cli][options][outfit]") {
  nlohmann::json keys = scene_keys();
  keys["garment"] = {"inner.obj", "outer.obj"};
  keys["no_fit"] = {"inner.txt", "outer.txt"};
  keys["source_body"] = "body.obj";
  keys["layer_order"] = {"outer", "inner"};
  keys["split"] = true;
  keys["write_avatar"] = true;
  const RetargetOptions options = retarget_options_from_json(keys);
  CHECK(options.inputs.garment == "inner.obj");
  CHECK(options.inputs.no_fit == "inner.txt");
  CHECK(options.inputs.source_body == "body.obj");
  REQUIRE(options.inputs.more_garments.size() == 1);
  CHECK(options.inputs.more_garments[0].garment == "outer.obj");
  CHECK(options.inputs.more_garments[0].no_fit == "outer.txt");
  CHECK(options.inputs.more_garments[0].source_body.empty());
  CHECK(options.layer_order == std::vector<std::string>{"outer", "inner"});
  CHECK(options.split);
  CHECK(options.write_avatar);

  // One garment stays one garment.
  CHECK(retarget_options_from_json(scene_keys()).inputs.more_garments.empty());
  keys["source_skeleton"] = {"s1.obj", "s2.obj", "s3.obj"};
  keys["target_skeleton"] = "t.obj";
  CHECK_THROWS_WITH(retarget_options_from_json(keys), Catch::Contains("--source-skeleton"));
}

}  // namespace gr

namespace gr {

TEST_CASE("the format option takes exactly the registered mesh formats",
          "[cli][options][formats]") {
  int exit_code = 0;
  const std::unique_ptr<CLI::App> app = make_command_line(exit_code);
  const std::string help = app->get_subcommand("retarget")->help();
  std::string choices;
  for (const std::string& name : mesh_format_names())
    choices += (choices.empty() ? "{" : ",") + name;
  CHECK(help.find("--format TEXT:" + choices + "}") != std::string::npos);
  for (const MeshFormat* format : mesh_formats()) {
    nlohmann::json keys = {{"garment", "g.obj"}, {"avatar", "a.obj"}, {"out", "out"}};
    keys["format"] = format->name;
    CHECK(retarget_options_from_json(keys).format == format);
  }
  nlohmann::json unknown = {{"garment", "g.obj"}, {"avatar", "a.obj"}, {"out", "out"}};
  CHECK(retarget_options_from_json(unknown).format == nullptr);
  unknown["format"] = "stl";
  CHECK_THROWS_AS(retarget_options_from_json(unknown), CLI::ValidationError);
}

}  // namespace gr
