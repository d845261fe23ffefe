#include <catch2/catch.hpp>

#include "core/inflation/avatar_inflation.hpp"
#include "core/inflation/synthetic_scene.hpp"
#include "validate/checks/mesh_intersections.hpp"

using namespace gr;

TEST_CASE("inflation output is certified free of the avatar by exact predicates",
          "[validate][inflation][integration]") {
  const GarmentScene scene = test::inflating_sphere_scene();
  // The starting garment crosses the full-size avatar, not the shrunk one.
  TriangleMesh shrunk{scene.shrunk_avatar, scene.avatar.faces};
  CHECK(find_intersecting_face_pairs(scene.garment, scene.avatar, 1).count > 0);
  CHECK(find_intersecting_face_pairs(scene.garment, shrunk, 1).count == 0);

  const InflationResult result = inflate_avatar(scene, RetargetParameters{});
  INFO(result.message);
  REQUIRE(result.succeeded());
  const TriangleMesh garment{result.garment, scene.garment.faces};
  const FacePairList crossings = find_intersecting_face_pairs(garment, scene.avatar, 5);
  CHECK(crossings.count == 0);
}
