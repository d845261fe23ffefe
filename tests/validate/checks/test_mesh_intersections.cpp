#include <catch2/catch.hpp>

#include "validate/checks/mesh_intersections.hpp"
#include "validate/validate_test_meshes.hpp"

using gr::Vector3d;
using gr::test::triangle;

namespace {

/// The unit right triangle in the plane z = 0.
gr::TriangleMesh base() { return triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}); }

bool intersect(const gr::TriangleMesh& a, const gr::TriangleMesh& b) {
  const gr::FacePairList found = gr::find_intersecting_face_pairs(a, b);
  return found.count > 0;
}

}  // namespace

TEST_CASE("crossing triangles intersect", "[validate][intersection]") {
  const auto vertical = triangle({0.2, 0.2, -0.5}, {0.3, 0.2, 0.5}, {0.25, 0.3, 0.5});
  CHECK(intersect(base(), vertical));
  CHECK(intersect(vertical, base()));
}

TEST_CASE("touching counts as intersecting - a gap of 1e-12 does not", "[validate][intersection]") {
  const double offset = GENERATE(0.0, 1e-12, -1e-12);
  CAPTURE(offset);
  SECTION("vertex on the other triangle's interior") {
    const auto above = triangle({0.25, 0.25, offset}, {0.25, 0.25, 1}, {0.5, 0.25, 1});
    CHECK(intersect(base(), above) == (offset <= 0));
  }
  SECTION("vertex on vertex") {
    const auto above = triangle({0, 0, offset}, {-1, 0, 1}, {0, -1, 1});
    CHECK(intersect(base(), above) == (offset == 0));
  }
  SECTION("along an edge") {
    // Its top edge lies on the base's edge y = 0 (x in [0.2, 0.8]) when offset is 0.
    const auto wall = triangle({0.2, -offset, 0}, {0.8, -offset, 0}, {0.5, -offset, -1});
    CHECK(intersect(base(), wall) == (offset <= 0));  // offset < 0 puts the wall inside
  }
  SECTION("coplanar overlap") {
    const auto shifted = triangle({0.1, 0.1, offset}, {1.1, 0.1, offset}, {0.1, 1.1, offset});
    CHECK(intersect(base(), shifted) == (offset == 0));
  }
}

TEST_CASE("nearly parallel triangles are decided exactly", "[validate][intersection]") {
  // A plane tilted by 1e-9 over the unit triangle: z = height - slope/2 + slope * x.
  const double slope = 1e-9;
  const double height = GENERATE(-0.5e-9, 0.25e-9, 0.5e-9, 0.5e-9 + 1e-12, 2e-9);
  CAPTURE(height);
  const auto tilted = triangle({0, 0, height - 0.5 * slope}, {1, 0, height + 0.5 * slope},
                               {0, 1, height - 0.5 * slope});
  // The tilted triangle spans z in [height - slope/2, height + slope/2]; it meets z = 0
  // within the base exactly when that range contains 0.
  CHECK(intersect(base(), tilted) == (std::abs(height) <= 0.5 * slope));
}

TEST_CASE("degenerate faces are tested as segments and points", "[validate][intersection]") {
  SECTION("a collinear face crossing a triangle") {
    const auto needle = triangle({0.2, 0.2, -1}, {0.2, 0.2, 0}, {0.2, 0.2, 1});
    CHECK(intersect(base(), needle));
  }
  SECTION("a collinear face beside a triangle") {
    const auto needle = triangle({2, 2, -1}, {2, 2, 0}, {2, 2, 1});
    CHECK_FALSE(intersect(base(), needle));
  }
  SECTION("a point face on a triangle") {
    const auto dot = triangle({0.3, 0.3, 0}, {0.3, 0.3, 0}, {0.3, 0.3, 0});
    CHECK(intersect(base(), dot));
  }
}

TEST_CASE("intersecting pairs are all counted, sorted and listed up to the limit",
          "[validate][intersection]") {
  // Three vertical triangles, each crossing the base at a different x.
  auto walls = gr::test::concatenate(
      triangle({0.1, 0.05, -1}, {0.1, 0.05, 1}, {0.15, 0.1, 0}),
      gr::test::concatenate(triangle({5, 5, 5}, {6, 5, 5}, {5, 6, 5}),
                            triangle({0.3, 0.05, -1}, {0.3, 0.05, 1}, {0.35, 0.1, 0})));
  const gr::FacePairList all = gr::find_intersecting_face_pairs(walls, base());
  REQUIRE(all.count == 2);
  CHECK(all.pairs[0].first == 0);
  CHECK(all.pairs[1].first == 2);
  const gr::FacePairList one = gr::find_intersecting_face_pairs(walls, base(), 1);
  CHECK(one.count == 2);
  REQUIRE(one.pairs.size() == 1);
  CHECK(one.pairs[0].first == 0);
}
