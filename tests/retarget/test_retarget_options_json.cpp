#include <limits>
#include <stdexcept>

#include <catch2/catch.hpp>

#include "core/io/formats/mesh_formats.hpp"
#include "retarget/retarget_options_json.hpp"

namespace gr {

namespace {

/// Options with every nested struct away from its defaults.
RetargetOptions unusual_options() {
  RetargetOptions o;
  o.inputs.garment = "g.glb";
  o.inputs.avatar = "a.obj";
  o.inputs.avatar_meshes = {"body", "head"};
  o.inputs.source_body_meshes = {"b"};
  o.inputs.more_garments = {GarmentPaths{"h.obj", "", "h-no-fit.txt", "hs.obj", "hb.obj"}};
  o.out_dir = "out";
  o.skirt_layers = {"h"};
  o.shrink_mode = ShrinkMode::kSkeleton;
  o.quality = Quality::kAccurate;
  o.fit_mode = FitMode::kTight;
  o.overrides.set("w_fit", 10.0);
  o.inference.binding = BindingChoice::kHeat;
  o.inference.binding_options.resolution = 64;
  o.inference.no_fit.hip_offset = 0.125;
  o.shape_thresholds.max_scale = std::numeric_limits<double>::infinity();
  o.shape_thresholds.enabled = false;
  o.threads = 3;
  o.format = &mesh_format_named("glb");
  o.split = true;
  o.layer_order = {"h", "g"};
  o.skin_transfer.max_angle_degrees = 12.5;
  o.limits.timeout_seconds = 30.0;
  o.write_in_place = true;
  o.open_pierced_faces = false;
  return o;
}

}  // namespace

TEST_CASE("typed retarget options survive their JSON field by field", "[options][json]") {
  const RetargetOptions given = unusual_options();
  const nlohmann::json written = retarget_options_to_json(given);
  // Through text, as the batch's job process reads them.
  const RetargetOptions read =
      retarget_options_from_typed_json(nlohmann::json::parse(written.dump()));
  CHECK(retarget_options_to_json(read) == written);
  CHECK(read.inputs.more_garments.size() == 1);
  CHECK(read.inputs.more_garments[0].source_body == "hb.obj");
  CHECK(read.shrink_mode == ShrinkMode::kSkeleton);
  CHECK(read.quality == Quality::kAccurate);
  CHECK(read.overrides.get("w_fit") == 10.0);
  CHECK(read.inference.binding == BindingChoice::kHeat);
  CHECK(read.inference.binding_options.resolution == 64);
  CHECK(read.shape_thresholds.max_scale == std::numeric_limits<double>::infinity());
  CHECK(read.format == &mesh_format_named("glb"));
  CHECK_FALSE(read.open_pierced_faces);
  CHECK(retarget_options_to_json(retarget_options_from_typed_json(retarget_options_to_json(
            RetargetOptions{}))) == retarget_options_to_json(RetargetOptions{}));
  CHECK(retarget_options_from_typed_json(retarget_options_to_json(RetargetOptions{})).format ==
        nullptr);
}

TEST_CASE("typed retarget options refuse a missing, unknown or mistyped field by name",
          "[options][json]") {
  const nlohmann::json written = retarget_options_to_json(unusual_options());
  const auto refusal = [](const nlohmann::json& object) -> std::string {
    try {
      retarget_options_from_typed_json(object);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  nlohmann::json missing = written;
  missing["limits"].erase("max_faces");
  CHECK_THAT(refusal(missing), Catch::Contains("limits.max_faces") && Catch::Contains("missing"));
  nlohmann::json unknown = written;
  unknown["inputs"]["colour"] = "red";
  CHECK_THAT(refusal(unknown), Catch::Contains("inputs"));
  nlohmann::json mistyped = written;
  mistyped["threads"] = "three";
  CHECK_THAT(refusal(mistyped), Catch::Contains("threads"));
  nlohmann::json format = written;
  format["format"] = "stl";
  CHECK_THAT(refusal(format), Catch::Contains("stl"));
}

}  // namespace gr
