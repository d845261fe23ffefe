#include <array>
#include <cmath>
#include <random>

#include <catch2/catch.hpp>

#include "core/broad_phase/pair_separation.hpp"
#include "core/distance/edge_edge_distance.hpp"
#include "core/distance/point_triangle_distance.hpp"

using gr::Vector3d;

namespace {

using Stencil = std::array<Vector3d, 4>;

double distance(const Stencil& x, int split) {
  const double d_sq = split == 1 ? gr::point_triangle_distance_sq(x[0], x[1], x[2], x[3])
                                 : gr::edge_edge_distance_sq(x[0], x[1], x[2], x[3]);
  return std::sqrt(d_sq);
}

Stencil lerp(const Stencil& x0, const Stencil& x1, double t) {
  Stencil x;
  for (int i = 0; i < 4; ++i) x[i] = x0[i] + t * (x1[i] - x0[i]);
  return x;
}

}  // namespace

TEST_CASE("pair separation bound never exceeds the distance along the motion",
          "[broad_phase][separation]") {
  const int split = GENERATE(1, 2);
  const double spread = GENERATE(0.1, 1.0, 3.0);  // how far apart the primitives start
  CAPTURE(split, spread);
  std::mt19937 rng(11);
  std::normal_distribution<double> normal(0.0, 1.0);
  const auto random_point = [&](double scale) -> Vector3d {
    return Vector3d(normal(rng), normal(rng), normal(rng)) * scale;
  };
  int separated = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    Stencil x0, x1;
    const Vector3d offset = random_point(spread);
    // Half of them static; a quarter also carried along by a common translation.
    const Vector3d carried = trial % 4 == 3 ? random_point(2.0) : Vector3d::Zero();
    for (int i = 0; i < 4; ++i) {
      x0[i] = random_point(0.5) + (i >= split ? offset : Vector3d::Zero());
      x1[i] = x0[i] + random_point(trial % 2 == 0 ? 0.0 : 0.3) + carried;
    }
    const double bound = gr::pair_separation_lower_bound(x0, x1, split);
    REQUIRE(bound >= 0.0);
    if (bound > 0.0) ++separated;
    for (const double t : {0.0, 0.25, 0.5, 0.75, 1.0}) {
      CAPTURE(trial, t, bound);
      REQUIRE(bound <= distance(lerp(x0, x1, t), split) + 1e-12);
    }
  }
  if (spread > 1.0) CHECK(separated > 1000);
}

TEST_CASE("pair separation bound separates mesh neighbours whose boxes overlap",
          "[broad_phase][separation]") {
  // Two edges side by side in a flat strip (a grid's 2-ring), boxes overlapping: the bound
  // along the centroid line sees the gap that the boxes do not.
  const Stencil edges = {Vector3d(0, 0, 0), Vector3d(1, 1, 0), Vector3d(0.6, 0, 0),
                         Vector3d(1.6, 1, 0)};
  const double gap = distance(edges, 2);
  const double bound = gr::pair_separation_lower_bound(edges, 2);
  CHECK(bound > 0.5 * gap);
  CHECK(bound <= gap + 1e-12);
  // A point above a tilted triangle: the triangle's normal separates them.
  const Stencil above = {Vector3d(0.5, 0.5, 0.6), Vector3d(0, 0, 0), Vector3d(1, 0, 0.5),
                         Vector3d(0, 1, 0.5)};
  CHECK(gr::pair_separation_lower_bound(above, 1) > 0.0);
  CHECK(gr::pair_separation_lower_bound(above, 1) <= distance(above, 1) + 1e-12);
  // Degenerate: coincident primitives and a zero-length edge give 0, never NaN.
  const Stencil coincident = {Vector3d(0, 0, 0), Vector3d(0, 0, 0), Vector3d(0, 0, 0),
                              Vector3d(0, 0, 0)};
  CHECK(gr::pair_separation_lower_bound(coincident, 2) == 0.0);
  CHECK(gr::pair_separation_lower_bound(coincident, 1) == 0.0);
}

TEST_CASE("pair separation bound follows a pair carried along together",
          "[broad_phase][separation]") {
  // A point 0.1 above a triangle, both moved 5 units sideways: the swept hulls overlap, yet
  // the gap never changes, and the bound in the pair's moving frame sees it.
  const int split = GENERATE(1, 2);
  Stencil x0 = split == 1 ? Stencil{Vector3d(0.2, 0.2, 0.1), Vector3d(0, 0, 0), Vector3d(1, 0, 0),
                                    Vector3d(0, 1, 0)}
                          : Stencil{Vector3d(0, 0, 0.1), Vector3d(1, 0, 0.1),
                                    Vector3d(0.5, -0.5, 0), Vector3d(0.5, 0.5, 0)};
  Stencil x1 = x0;
  for (Vector3d& p : x1) p += Vector3d(5.0, -3.0, 0.4);
  const double bound = gr::pair_separation_lower_bound(x0, x1, split);
  CHECK(bound == Approx(0.1).margin(1e-12));
  for (const double t : {0.0, 0.5, 1.0}) CHECK(bound <= distance(lerp(x0, x1, t), split) + 1e-12);
}
