// The shared assets through the validator: every garment as given, placed on every avatar
// by the skeleton normalization, intersects it. The avatars' own overlapping parts are
// never reported: moved away from the avatar, each garment is clean of it.
#include <catch2/catch.hpp>

#include "retarget/scene/normalization.hpp"
#include "retarget/scene/scene.hpp"
#include "test_support.hpp"
#include "validate/certify/validation.hpp"

TEST_CASE("each shared garment placed on each shared avatar intersects it",
          "[validate][shared-data]") {
  const std::string garment_name = GENERATE(as<std::string>{}, "skirt", "puffer");
  const std::string avatar_name = GENERATE(as<std::string>{}, "foxgirl", "goblin");
  CAPTURE(garment_name, avatar_name);
  gr::ScenePaths paths;
  paths.garment = gr::test::shared_data("garments/" + garment_name + "/garment.obj");
  paths.source_skeleton = gr::test::shared_data("garments/" + garment_name + "/skeleton.obj");
  paths.avatar = gr::test::shared_data("avatars/" + avatar_name + "/avatar.obj");
  paths.target_skeleton = gr::test::shared_data("avatars/" + avatar_name + "/skeleton.obj");
  const gr::Scene scene = gr::load_scene(paths);
  const gr::Normalization normalization = gr::normalize_scene(scene);
  gr::TriangleMesh garment = gr::mesh_as_written(scene.garment_document);
  gr::TriangleMesh avatar = gr::mesh_as_written(scene.avatar_document);
  garment.vertices = normalization.garment_to_scene.apply_rows(garment.vertices);
  avatar.vertices = normalization.avatar_to_scene.apply_rows(avatar.vertices);

  const gr::ValidationResult placed = gr::validate_meshes({garment}, avatar, {});
  REQUIRE(placed.garments.size() == 1);
  const gr::GarmentFindings& g = placed.garments[0];
  CHECK(g.avatar_intersections.count > 0);
  CHECK_FALSE(placed.certified());
  CHECK(g.avatar_clearance.distance == 0.0);
  for (const gr::FacePair& p : g.avatar_intersections.pairs) {
    REQUIRE(p.first >= 0);
    REQUIRE(p.first < garment.faces.rows());
    REQUIRE(p.second >= 0);
    REQUIRE(p.second < avatar.faces.rows());
  }

  SECTION("moved clear of the avatar: no garment-avatar fault, whatever the avatar's overlaps") {
    const double avatar_width =
        avatar.vertices.col(0).maxCoeff() - avatar.vertices.col(0).minCoeff();
    const double garment_width =
        garment.vertices.col(0).maxCoeff() - garment.vertices.col(0).minCoeff();
    garment.vertices.col(0).array() += avatar_width + garment_width + 1.0;
    const gr::ValidationResult apart = gr::validate_meshes({garment}, avatar, {});
    const gr::GarmentFindings& h = apart.garments[0];
    CHECK(h.avatar_intersections.count == 0);
    CHECK(h.avatar_clearance.distance > 0.5);
    CHECK(h.clearance_has_points);
    // Self-intersections belong to the garment and do not depend on where it is.
    CHECK(h.self_intersections.pairs.count == g.self_intersections.pairs.count);
    CHECK(apart.certified() == (h.self_intersections.pairs.count == 0));
  }
}
