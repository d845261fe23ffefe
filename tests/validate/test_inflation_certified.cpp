#include <catch2/catch.hpp>

#include "core/inflation/avatar_inflation.hpp"
#include "core/inflation/synthetic_scene.hpp"
#include "validate/checks/mesh_intersections.hpp"

using namespace gr;

TEST_CASE("inflation output is certified free of the avatar by exact predicates",
          "[validate][inflation][integration]") {
  // The garment (closed, radius 0.9) starts inside the avatar (closed, convex, inscribed
  // in the unit sphere) and outside the shrunk avatar (radius 0.5).
  const GarmentScene scene = test::inflating_sphere_scene();
  const TriangleMesh shrunk{scene.shrunk_avatar, scene.avatar.faces};
  CHECK(find_intersecting_face_pairs(scene.garment, shrunk, 1).count == 0);
  CHECK(scene.garment.vertices.rowwise().norm().maxCoeff() < 1.0);

  const InflationResult result = inflate_avatar(scene, RetargetParameters{});
  INFO(result.message);
  REQUIRE(result.succeeded());
  const TriangleMesh garment{result.garment, scene.garment.faces};
  const FacePairList crossings = find_intersecting_face_pairs(garment, scene.avatar, 5);
  CHECK(crossings.count == 0);
  // Two closed surfaces that do not cross are nested or apart: one garment vertex outside
  // the unit sphere (so outside the avatar) puts the whole garment outside.
  CHECK(result.garment.rowwise().norm().maxCoeff() > 1.0);
}
