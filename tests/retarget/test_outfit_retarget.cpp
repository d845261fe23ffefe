// Outfits: several garments retargeted together as layers, certified as a whole.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/common/errors.hpp"
#include "core/io/formats/mesh_formats.hpp"
#include "core/io/gltf_document.hpp"
#include "core/io/obj_document.hpp"
#include "core/io/rig_files.hpp"
#include "extremes_support.hpp"
#include "garment/outfit_meshes.hpp"
#include "retarget/run/progress.hpp"
#include "retarget/stages/outfit_stage.hpp"
#include "retarget/stages/read_stage.hpp"

namespace gr {
namespace {

using test::NestedSleeves;

/// Options for the sleeves given in `order` (indices into NestedSleeves::sleeves).
RetargetOptions outfit_options(const NestedSleeves& scene, const std::vector<int>& order) {
  RetargetOptions options = test::quiet_options(scene.sleeves[static_cast<std::size_t>(order[0])],
                                                scene.avatar, scene.dir / "out");
  for (std::size_t k = 1; k < order.size(); ++k)
    options.inputs.more_garments.push_back({scene.sleeves[static_cast<std::size_t>(order[k])]});
  options.inputs.source_body = scene.source_body;
  options.overrides.set("voxel_size", test::kSyntheticVoxelSize);
  options.overrides.set("max_newton_iterations", test::kSyntheticNewtonCap);
  return options;
}

}  // namespace

TEST_CASE("outfit: three nested sleeves are certified as a whole, in their order",
          "[pipeline][outfit]") {
  const NestedSleeves scene = test::write_nested_sleeves(test::fresh_temp_dir("outfit_sleeves"));
  // Given out of order: the run measures inside to outside on the source.
  const RetargetResult result = test::run_and_check(outfit_options(scene, {1, 2, 0}));
  INFO(result.message);
  REQUIRE(result.status == Outcome::kCertified);
  const RetargetReport& r = result.report;
  REQUIRE(r.outfit.has_value());
  const OutfitReport& outfit = *r.outfit;
  CHECK(outfit.order_from == "measured");
  CHECK(outfit.order == std::vector<std::string>{"inner", "middle", "outer"});
  CHECK(outfit.source.rays_meeting_layers > 0);
  CHECK(outfit.source.out_of_order == 0);
  CHECK(outfit.result.rays_meeting_layers > 0);
  CHECK(outfit.result.out_of_order == 0);
  CHECK(outfit.order_kept);
  CHECK(outfit.layer_intersections == 0);
  REQUIRE(outfit.layers.size() == 3);
  for (const OutfitLayerReport& layer : outfit.layers) {
    INFO(layer.name);
    CHECK(std::filesystem::exists(layer.written));
    CHECK(layer.shape.mean_edge_change <= 0.15);
  }
  // Every garment against every other, in the certificate.
  const nlohmann::json certificate =
      nlohmann::json::parse(std::ifstream(scene.dir / "out" / "certificate.json"));
  CHECK(certificate["garment_pairs"].size() == 3);
  CHECK(certificate["garments"].size() == 3);
  // The body under the middle of the sleeves is hidden; its ends are not.
  CHECK(outfit.hidden_faces > 0);
  CHECK(outfit.hidden_faces < outfit.avatar_faces / 2);
  CHECK(std::filesystem::exists(scene.dir / "out" / "hidden-avatar-faces.txt"));
  // Inferred no-fit lists, one per garment in its own numbering, that --no-fit reads back.
  CHECK(r.inferred.no_fit_inferred);
  CHECK_FALSE(std::filesystem::exists(scene.dir / "out" / "no-fit.txt"));
  REQUIRE(r.inferred.no_fit_layer_paths.size() == 3);
  for (const std::string name : {"middle", "outer", "inner"}) {
    const std::filesystem::path list = scene.dir / "out" / (name + ".no-fit.txt");
    REQUIRE(std::filesystem::exists(list));
    const std::size_t rows =
        static_cast<std::size_t>(read_obj((scene.dir / (name + ".obj")).string()).positions.rows());
    CHECK_NOTHROW(read_vertex_list(list.string(), static_cast<int>(rows)));
  }
}

TEST_CASE("outfit: a layer whose own shape changed beyond a threshold flags the run",
          "[pipeline][outfit]") {
  const NestedSleeves scene =
      test::write_nested_sleeves(test::fresh_temp_dir("outfit_layer_shape"));
  RetargetOptions options = outfit_options(scene, {0, 1, 2});
  const RetargetResult first = test::run_and_check(options);
  REQUIRE(first.status == Outcome::kCertified);
  REQUIRE(first.report.outfit.has_value());
  const double whole = first.report.certify.shape.mean_edge_change;
  double largest = 0.0;
  for (const OutfitLayerReport& layer : first.report.outfit->layers)
    largest = std::max(largest, layer.shape.mean_edge_change);
  // A limit the outfit counted as one keeps to and one layer does not.
  REQUIRE(largest > 1.01 * whole);
  options.shape_thresholds.mean_edge_change = 0.5 * (whole + largest);
  const RetargetResult second = test::run_and_check(options);
  INFO(second.message);
  CHECK(second.status == Outcome::kShapeChanged);
  CHECK(second.report.certify.shape.mean_edge_change < options.shape_thresholds.mean_edge_change);
  // report.json names the layer beyond the limit, and only layers beyond it.
  const nlohmann::json report =
      nlohmann::json::parse(std::ifstream(scene.dir / "out" / "report.json"));
  int beyond = 0;
  for (const nlohmann::json& layer : report["outfit"]["layers"]) {
    const bool within = layer["shape"]["within_thresholds"].get<bool>();
    CHECK(within == (layer["shape"]["mean_edge_change"].get<double>() <=
                     options.shape_thresholds.mean_edge_change));
    beyond += within ? 0 : 1;
  }
  CHECK(beyond >= 1);
  CHECK(report["shape"]["within_thresholds"].get<bool>());
}

TEST_CASE("outfit: layers denser than twice the proxy are solved coarse to fine, certified",
          "[pipeline][outfit][coarse_to_fine]") {
  const NestedSleeves scene = test::write_nested_sleeves(test::fresh_temp_dir("outfit_proxy"));
  RetargetOptions options = outfit_options(scene, {0, 1, 2});
  // Each sleeve has 704 faces: over twice 300, so the outfit has a proxy, each layer
  // decimated to about 300 faces.
  options.overrides.set("proxy_faces", 300);
  const RetargetResult result = test::run_and_check(options);
  INFO(result.message);
  REQUIRE(result.status == Outcome::kCertified);
  const RetargetReport& r = result.report;
  INFO(r.proxy.reason);
  REQUIRE(r.proxy.used);
  CHECK(r.proxy.faces >= 3 * 250);
  CHECK(r.proxy.faces <= 3 * 350);
  CHECK(r.proxy.inflate_path.reached_end);
  REQUIRE(r.outfit.has_value());
  CHECK(r.outfit->order == std::vector<std::string>{"inner", "middle", "outer"});
  CHECK(r.outfit->order_kept);
  CHECK(r.outfit->result.out_of_order == 0);
  for (const OutfitLayerReport& layer : r.outfit->layers) {
    INFO(layer.name);
    CHECK(layer.shape.mean_edge_change <= 0.15);
  }

  // Below twice the proxy per layer, the outfit is solved directly, whatever its total.
  options.overrides.set("proxy_faces", 400);
  options.out_dir = (scene.dir / "direct").string();
  const RetargetResult direct = test::run_and_check(options);
  REQUIRE(direct.status == Outcome::kCertified);
  CHECK_FALSE(direct.report.proxy.used);
  CHECK_THAT(direct.report.proxy.reason, Catch::Contains("largest layer's 704 faces"));
}

TEST_CASE("outfit: a given layer order is used, and one the result contradicts is reported",
          "[pipeline][outfit]") {
  const NestedSleeves scene =
      test::write_nested_sleeves(test::fresh_temp_dir("outfit_given_order"));
  RetargetOptions options = outfit_options(scene, {0, 1, 2});
  options.layer_order = {"outer", "middle", "inner"};
  const RetargetResult result = test::run_and_check(options);
  REQUIRE(result.report.outfit.has_value());
  const OutfitReport& outfit = *result.report.outfit;
  CHECK(outfit.order_from == "given");
  CHECK(outfit.order == std::vector<std::string>{"outer", "middle", "inner"});
  // Every ray meets the inner sleeve first: the order given is contradicted everywhere.
  CHECK(outfit.source.out_of_order == outfit.source.rays_meeting_layers);
  CHECK(outfit.result.out_of_order > 0);

  options.layer_order = {"outer", "nowhere", "inner"};
  CHECK_THROWS_AS(run_retarget(options), InputError);
}

TEST_CASE("outfit: a garment given twice is refused before the solve, nothing written",
          "[pipeline][outfit]") {
  const NestedSleeves scene = test::write_nested_sleeves(test::fresh_temp_dir("outfit_twice"));
  RetargetOptions options = outfit_options(scene, {0, 1, 0});
  REQUIRE_THROWS_WITH(run_retarget(options), Catch::Contains("lies exactly where garment") &&
                                                 Catch::Contains("given twice"));
  CHECK_FALSE(std::filesystem::exists(scene.dir / "out"));
  // A copy moved by a hair of its size is another garment.
  options = outfit_options(scene, {0, 1});
  ObjDocument moved = read_obj(scene.sleeves[0]);
  moved.positions.col(0).array() += 1e-6;
  const std::filesystem::path copy = scene.dir / "inner_moved.obj";
  write_obj(copy.string(), moved, moved.positions);
  options.inputs.more_garments.push_back({copy.string()});
  CHECK_NOTHROW(load_scene(options.inputs));
}

}  // namespace gr

namespace gr {

TEST_CASE("outfit: written as one GLB with a mesh per garment, or a GLB each when split",
          "[pipeline][outfit][gltf]") {
  const NestedSleeves scene = test::write_nested_sleeves(test::fresh_temp_dir("outfit_glb"));
  RetargetOptions options = outfit_options(scene, {0, 1, 2});
  options.format = &mesh_format_named("glb");
  SECTION("one file") {
    const RetargetResult result = run_retarget(options);
    INFO(result.message);
    REQUIRE(result.status == Outcome::kCertified);
    const std::filesystem::path written = scene.dir / "out" / "outfit.glb";
    CHECK(result.garment_path == written.string());
    CHECK(gltf_mesh_names(written.string()) ==
          std::vector<std::string>{"inner", "middle", "outer"});
    // Each mesh read back is its garment: as many triangles as the sleeve it came from.
    for (const std::string name : {"inner", "middle", "outer"})
      CHECK(read_gltf(written.string(), name).document.faces.size() ==
            read_obj((scene.dir / (name + ".obj")).string()).faces.size());
    REQUIRE(result.report.outfit.has_value());
    for (const OutfitLayerReport& layer : result.report.outfit->layers) {
      CHECK(layer.written == written.string());
      CHECK(layer.written_mesh == layer.name);
    }
  }
  SECTION("split") {
    options.split = true;
    const RetargetResult result = run_retarget(options);
    INFO(result.message);
    REQUIRE(result.status == Outcome::kCertified);
    CHECK_FALSE(std::filesystem::exists(scene.dir / "out" / "outfit.glb"));
    for (const std::string name : {"inner", "middle", "outer"})
      CHECK(std::filesystem::is_regular_file(scene.dir / "out" / (name + ".glb")));
  }
}

TEST_CASE("outfit: only the layers named skirts are skirts", "[pipeline][outfit]") {
  const NestedSleeves sleeves =
      test::write_nested_sleeves(test::fresh_temp_dir("outfit_skirt_layers"));
  const RetargetOptions options = outfit_options(sleeves, {0, 1, 2});
  Progress progress(true);
  Scene scene = run_read({options.inputs}, {}, progress).scene;
  REQUIRE(scene.layers.size() == 3);
  CHECK(skirt_vertices(scene).empty());  // no skirt: nothing marked

  mark_skirts(scene, false, {"middle"});
  CHECK_FALSE(scene.layers[0].skirt);
  CHECK(scene.layers[1].skirt);
  CHECK_FALSE(scene.layers[2].skirt);
  // Exactly the middle sleeve's vertices, in the welded garment's numbering.
  const std::vector<char> skirt = skirt_vertices(scene);
  REQUIRE(skirt.size() == static_cast<std::size_t>(scene.garment.mesh.vertices.rows()));
  std::vector<char> expected(skirt.size(), 0);
  const GarmentLayer& middle = scene.layers[1];
  for (int p = 0; p < middle.position_count; ++p)
    expected[static_cast<std::size_t>(
        scene.garment.obj_to_sim[static_cast<std::size_t>(middle.first_position + p)])] = 1;
  CHECK(skirt == expected);
  CHECK(std::count(skirt.begin(), skirt.end(), 1) > 0);

  mark_skirts(scene, true, {});  // --skirt alone: every garment
  for (const GarmentLayer& layer : scene.layers) CHECK(layer.skirt);
  CHECK_THROWS_AS(mark_skirts(scene, false, {"nowhere"}), InputError);
}

}  // namespace gr
