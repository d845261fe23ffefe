#include <catch2/catch.hpp>

#include "validate/checks/degenerate_faces.hpp"
#include "validate/checks/position_identity.hpp"
#include "validate/checks/self_intersections.hpp"
#include "validate/validate_test_meshes.hpp"

using gr::Vector2d;
using gr::test::make_mesh;

namespace {

std::size_t self_count(const gr::TriangleMesh& mesh) {
  return gr::find_self_intersecting_face_pairs(mesh).pairs.count;
}

}  // namespace

TEST_CASE("faces sharing an edge", "[validate][self]") {
  SECTION("flat, on opposite sides: clean") {
    CHECK(self_count(make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, -1, 0}},
                               {{0, 1, 2}, {1, 0, 3}})) == 0);
  }
  SECTION("bent: clean") {
    CHECK(self_count(make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0.5, 1}},
                               {{0, 1, 2}, {1, 0, 3}})) == 0);
  }
  SECTION("folded flat onto each other: intersecting") {
    CHECK(self_count(make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5, 2, 0}},
                               {{0, 1, 2}, {1, 0, 3}})) == 1);
  }
  SECTION("folded to within 1e-12 of flat: clean") {
    CHECK(self_count(make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5, 2, 1e-12}},
                               {{0, 1, 2}, {1, 0, 3}})) == 0);
  }
}

TEST_CASE("faces sharing one vertex", "[validate][self]") {
  SECTION("apart: clean") {
    CHECK(self_count(make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}},
                               {{0, 1, 2}, {0, 3, 4}})) == 0);
  }
  SECTION("coplanar, one inside the other's corner: intersecting") {
    CHECK(self_count(make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.2, 0.1, 0}, {0.1, 0.2, 0}},
                               {{0, 1, 2}, {0, 3, 4}})) == 1);
  }
  SECTION("coplanar, a long thin face through the other: intersecting") {
    CHECK(self_count(make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 2, 0}, {2.1, 1.9, 0}},
                               {{0, 1, 2}, {0, 3, 4}})) == 1);
  }
  SECTION("piercing the other face away from the vertex: intersecting") {
    CHECK(self_count(make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5, 0.2, -1}, {0.2, 0.5, 1}},
                               {{0, 1, 2}, {0, 3, 4}})) == 1);
  }
  SECTION("touching the other face only at the shared vertex, tilted: clean") {
    CHECK(self_count(make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, -1, 1}, {-1, -0.5, -1}},
                               {{0, 1, 2}, {0, 3, 4}})) == 0);
  }
}

TEST_CASE("faces sharing every corner (a duplicated face) intersect", "[validate][self]") {
  CHECK(self_count(make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}, {2, 1, 0}})) == 1);
}

TEST_CASE("rows at identical coordinates are one vertex", "[validate][self]") {
  // A UV seam: the shared edge is written twice as distinct `v` lines.
  const auto seam = make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 0}, {1, 0, 0}, {1, -1, 0}},
                              {{0, 1, 2}, {4, 3, 5}});
  CHECK(self_count(seam) == 0);
  const std::vector<int> identity = gr::position_identity(seam.vertices);
  CHECK(identity == std::vector<int>{0, 1, 2, 0, 1, 5});
  SECTION("-0.0 and 0.0 are the same coordinate") {
    const auto signed_zero = make_mesh({{0.0, 0, 0}, {-0.0, 0, 0}}, {{0, 1, 0}});
    CHECK(gr::position_identity(signed_zero.vertices) == std::vector<int>{0, 0});
  }
}

TEST_CASE("a garment folded through itself", "[validate][self]") {
  // Profile in the xz-plane: along x, up, then back down through the first segment at x = 1.5.
  const auto folded = gr::test::extruded_strip(
      {Vector2d(0, 0), Vector2d(1, 0), Vector2d(2, 0), Vector2d(2, 1), Vector2d(1, -1)});
  const gr::SelfIntersections found = gr::find_self_intersecting_face_pairs(folded);
  CHECK(found.pairs.count > 0);
  for (const gr::FacePair& p : found.pairs.pairs) {
    CAPTURE(p.first, p.second);
    CHECK(p.first / 2 == 1);   // the segment from x = 1 to 2 ...
    CHECK(p.second / 2 == 3);  // ... is crossed by the last one
  }
  SECTION("the same strip unfolded is clean") {
    const auto open = gr::test::extruded_strip(
        {Vector2d(0, 0), Vector2d(1, 0), Vector2d(2, 0), Vector2d(2, 1), Vector2d(3, 1)});
    CHECK(self_count(open) == 0);
  }
  SECTION("folded down onto itself without crossing: touching counts") {
    const auto touching = gr::test::extruded_strip(
        {Vector2d(0, 0), Vector2d(1, 0), Vector2d(2, 0), Vector2d(2, 1), Vector2d(1.5, 0)});
    CHECK(self_count(touching) > 0);
  }
}

TEST_CASE("a caller's candidates decide which pairs are tested", "[validate][self]") {
  const auto folded = gr::test::extruded_strip(
      {Vector2d(0, 0), Vector2d(1, 0), Vector2d(2, 0), Vector2d(2, 1), Vector2d(1, -1)});
  const std::vector<gr::FacePair> all = gr::find_self_intersecting_face_pairs(folded).pairs.pairs;
  REQUIRE(all.size() >= 2);
  // One crossing pair and one pair far apart: only the crossing one is found.
  const std::vector<gr::FacePair> some{all.front(), {0, all.front().second}};
  const gr::SelfIntersections found = gr::self_intersecting_among(folded, some);
  REQUIRE(found.pairs.count == 1);
  CHECK(found.pairs.pairs.front() == all.front());
  CHECK(gr::self_intersecting_among(folded, {}).pairs.count == 0);
}

TEST_CASE("degenerate faces are reported, never skipped silently", "[validate][self][degenerate]") {
  // Face 1 is collinear, face 2 repeats a corner, face 3 is a point; face 0 is fine.
  const auto mesh = make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {5, 5, 5}},
                              {{0, 1, 2}, {0, 1, 3}, {2, 2, 0}, {4, 4, 4}});
  CHECK(gr::find_degenerate_faces(mesh) == std::vector<int>{1, 2, 3});
  const gr::SelfIntersections found = gr::find_self_intersecting_face_pairs(mesh);
  // Faces 0, 1 and 2 are neighbours with a degenerate face among them; face 3 is alone.
  CHECK(found.untested_degenerate_neighbours == 3);
  CHECK(found.pairs.count == 0);
  SECTION("a degenerate face away from its neighbours is still tested") {
    // A collinear face (its own vertices) piercing face 0.
    const auto pierced =
        make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.2, 0.2, -1}, {0.2, 0.2, 0}, {0.2, 0.2, 1}},
                  {{0, 1, 2}, {3, 4, 5}});
    CHECK(gr::find_degenerate_faces(pierced) == std::vector<int>{1});
    CHECK(self_count(pierced) == 1);
  }
}
