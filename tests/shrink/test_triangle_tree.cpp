#include <cmath>
#include <random>

#include <catch2/catch.hpp>

#include "core/distance/point_triangle_distance.hpp"
#include "core/mesh/primitives.hpp"
#include "shrink/level_set/triangle_tree.hpp"
#include "shrink_oracles.hpp"

using namespace gr;

using test::brute_force_distance;
using test::brute_force_winding_number;

TEST_CASE("point-triangle distance against dense sampling", "[shrink][distance]") {
  const Vector3d a(0, 0, 0), b(1, 0, 0);
  const Vector3d c =
      GENERATE(Vector3d(0, 1, 0), Vector3d(2, 1e-12, 0), Vector3d(0.5, 0, 0), Vector3d(0, 0, 0));
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coordinate(-1.0, 2.0);
  for (int trial = 0; trial < 50; ++trial) {
    const Vector3d p(coordinate(rng), coordinate(rng), coordinate(rng));
    CAPTURE(c.transpose(), p.transpose());
    double sampled = std::numeric_limits<double>::infinity();
    const int n = 200;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j)
        sampled = std::min(sampled, (a + (b - a) * i / n + (c - a) * j / n - p).norm());
    const double exact = std::sqrt(point_triangle_distance_sq(p, a, b, c));
    REQUIRE(exact <= sampled + 1e-12);
    REQUIRE(exact >= sampled - 0.02);
  }
}

TEST_CASE("winding number of a closed sphere", "[shrink][winding]") {
  const TriangleMesh sphere = uv_sphere(0.5, Vector3d(0.1, -0.2, 0.3));
  const TriangleTree tree(sphere);
  REQUIRE(tree.winding_number(Vector3d(0.1, -0.2, 0.3)) == Approx(1.0).margin(1e-2));
  REQUIRE(tree.exact_winding_number(Vector3d(0.3, -0.1, 0.4)) == Approx(1.0).margin(1e-9));
  REQUIRE(tree.winding_number(Vector3d(2.0, 0.0, 0.0)) == Approx(0.0).margin(1e-3));
  REQUIRE(tree.exact_winding_number(Vector3d(0.1, -0.2, 0.85)) == Approx(0.0).margin(1e-9));
  REQUIRE(tree.distance_sq(Vector3d(0.1, -0.2, 1.3)) == Approx(0.25).epsilon(1e-3));
}

TEST_CASE("winding jumps along segments match winding number differences", "[shrink][winding]") {
  // On a closed surface the winding number changes only by its jumps.
  TriangleMesh sphere = uv_sphere(0.5, Vector3d(0.02, -0.01, 0.03), 12, 24);
  const bool inverted = GENERATE(false, true);
  if (inverted) sphere.faces.col(1).swap(sphere.faces.col(2));
  CAPTURE(inverted);
  const TriangleTree tree(sphere);
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> coordinate(-0.8, 0.8);
  int crossing = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Vector3d from(coordinate(rng), coordinate(rng), coordinate(rng));
    const Vector3d to = from + 0.5 * Vector3d(coordinate(rng), coordinate(rng), coordinate(rng));
    bool uncertain = true;
    const int jumps = tree.winding_jumps(from, to, 1e-9, &uncertain);
    CAPTURE(from.transpose(), to.transpose(), jumps);
    REQUIRE_FALSE(uncertain);
    REQUIRE(tree.exact_winding_number(from) + jumps ==
            Approx(tree.exact_winding_number(to)).margin(1e-9));
    crossing += jumps != 0;
  }
  CHECK(crossing > 30);

  SECTION("an end on a face or a crossing through an edge is uncertain") {
    const Vector3d a = sphere.vertices.row(sphere.faces(40, 0)).transpose();
    const Vector3d b = sphere.vertices.row(sphere.faces(40, 1)).transpose();
    const Vector3d c = sphere.vertices.row(sphere.faces(40, 2)).transpose();
    const Vector3d normal = (b - a).cross(c - a).normalized();
    bool uncertain = false;
    tree.winding_jumps((a + b + c) / 3.0, (a + b + c) / 3.0 + 0.1 * normal, 1e-9, &uncertain);
    REQUIRE(uncertain);
    const Vector3d on_edge = 0.5 * (a + b);
    tree.winding_jumps(on_edge - 0.1 * normal, on_edge + 0.1 * normal, 1e-9, &uncertain);
    REQUIRE(uncertain);
  }
}
