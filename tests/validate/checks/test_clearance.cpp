#include <catch2/catch.hpp>

#include "validate/checks/clearance.hpp"
#include "validate/validate_test_meshes.hpp"

using gr::test::make_mesh;
using gr::test::triangle;

TEST_CASE("clearance between separated meshes, with the closest faces", "[validate][clearance]") {
  // Avatar: two triangles at z = 0; garment: a far triangle and one hovering at z = 0.25
  // above the avatar's second face.
  const auto avatar =
      make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {10, 0, 0}, {11, 0, 0}, {10, 1, 0}},
                {{0, 1, 2}, {3, 4, 5}});
  const auto garment = make_mesh({{-5, -5, 3},
                                  {-4, -5, 3},
                                  {-5, -4, 3},
                                  {10.1, 0.1, 0.25},
                                  {10.6, 0.1, 0.25},
                                  {10.1, 0.6, 0.25}},
                                 {{0, 1, 2}, {3, 4, 5}});
  const gr::Clearance c = gr::minimum_clearance(garment, avatar);
  CHECK(c.distance == Approx(0.25).epsilon(1e-12));
  CHECK(c.first_face == 1);
  CHECK(c.second_face == 1);
  CHECK(c.first_point.z() == Approx(0.25));
  CHECK(c.second_point.z() == Approx(0.0).margin(1e-12));
  CHECK((c.first_point - c.second_point).norm() == Approx(c.distance));
}

TEST_CASE("clearance is measured in the meshes' own units", "[validate][clearance]") {
  const double scale = GENERATE(1e-3, 1.0, 1e3);
  CAPTURE(scale);
  const auto avatar = triangle({0, 0, 0}, {scale, 0, 0}, {0, scale, 0});
  const auto garment =
      triangle({0, 0, 0.1 * scale}, {scale, 0, 0.1 * scale}, {0, scale, 0.3 * scale});
  CHECK(gr::minimum_clearance(garment, avatar).distance == Approx(0.1 * scale).epsilon(1e-9));
}

TEST_CASE("garment vertices closer than a threshold", "[validate][clearance]") {
  const auto avatar = triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  // Heights 0.05, 0.2 and 0.05 + a duplicate row of the first (a UV seam), counted once.
  const auto garment =
      make_mesh({{0.1, 0.1, 0.05}, {0.5, 0.1, 0.2}, {0.1, 0.5, 0.05}, {0.1, 0.1, 0.05}},
                {{0, 1, 2}, {3, 1, 2}});
  CHECK(gr::vertices_closer_than(garment, avatar, 0.1) == std::vector<int>{0, 2});
  CHECK(gr::vertices_closer_than(garment, avatar, 0.05).empty());  // strictly closer
  CHECK(gr::vertices_closer_than(garment, avatar, 1.0) == std::vector<int>{0, 1, 2});
  SECTION("beside a degenerate avatar face, measured to its segment") {
    const auto needle = triangle({0, 0, 0}, {0, 0, 1}, {0, 0, 2});
    const auto point_garment = make_mesh({{0.01, 0, 1.5}, {5, 5, 5}, {5, 6, 5}}, {{0, 1, 2}});
    CHECK(gr::vertices_closer_than(point_garment, needle, 0.02) == std::vector<int>{0});
  }
}
