#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <catch2/catch.hpp>

#include "core/ccd/additive_ccd.hpp"
#include "core/ccd/ccd.hpp"
#include "core/distance/edge_edge_distance.hpp"
#include "core/distance/point_triangle_distance.hpp"

using gr::Vector3d;
using Stencil = std::array<Vector3d, 4>;

namespace {

double distance(const Stencil& x, bool edge_edge) {
  return std::sqrt(edge_edge ? gr::edge_edge_distance_sq(x[0], x[1], x[2], x[3])
                             : gr::point_triangle_distance_sq(x[0], x[1], x[2], x[3]));
}

Stencil at(const Stencil& x0, const Stencil& x1, double t) {
  Stencil x;
  for (int i = 0; i < 4; ++i) x[i] = x0[i] + t * (x1[i] - x0[i]);
  return x;
}

/// Runs the pair's CCD and checks that on densely sampled times in [0, step] the pair
/// keeps the separation (ratio times its starting distance). Returns the step.
double checked_step(const Stencil& x0, const Stencil& x1, bool edge_edge,
                    const gr::CcdOptions& options = {}) {
  const double step =
      edge_edge ? gr::edge_edge_ccd(x0, x1, options) : gr::point_triangle_ccd(x0, x1, options);
  const double d0 = distance(x0, edge_edge);
  // A pair that starts below the absolute floor is held to the ratio only.
  const double separation =
      d0 <= options.min_separation
          ? options.min_separation_ratio * d0
          : std::max(options.min_separation_ratio * d0, options.min_separation);
  CAPTURE(step, d0, separation);
  REQUIRE(step >= 0.0);
  REQUIRE(step <= 1.0);
  const int samples = 20000;
  double closest = std::numeric_limits<double>::infinity();
  for (int k = 0; k <= samples; ++k)
    closest = std::min(closest, distance(at(x0, x1, step * k / samples), edge_edge));
  if (step > 0.0) CHECK(closest >= separation * (1.0 - 1e-9));
  return step;
}

Stencil triangle_with(const Vector3d& p) {
  return {p, Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0)};
}

}  // namespace

TEST_CASE("CCD: a vertex tunnelling through a triangle at high speed", "[ccd]") {
  const double speed = GENERATE(2.0, 1e3, 1e8);
  const Stencil x0 = triangle_with(Vector3d(0.25, 0.25, 1.0));
  const Stencil x1 = triangle_with(Vector3d(0.25, 0.25, 1.0 - speed));
  const double step = checked_step(x0, x1, false);
  const double contact = 1.0 / speed;
  CHECK(step < contact);
  CHECK(step > 0.8 * contact);  // stops near the separation, not far before it
}

TEST_CASE("CCD: parallel edges sliding through each other", "[ccd]") {
  const double angle = GENERATE(0.0, 1e-10, 1e-4);
  const Vector3d along(std::cos(angle), std::sin(angle), 0.0);
  const Stencil x0{Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0.2, 0, 0.1),
                   Vector3d(0.2, 0, 0.1) + along};
  Stencil x1 = x0;
  x1[2] += Vector3d(0.3, 0, -0.2);
  x1[3] += Vector3d(0.3, 0, -0.2);
  const double step = checked_step(x0, x1, true);
  CHECK(step < 0.5);
  CHECK(step > 0.3);
}

TEST_CASE("CCD: motion exactly in a triangle's plane", "[ccd]") {
  SECTION("through an edge") {
    const Stencil x0 = triangle_with(Vector3d(-0.5, 0.3, 0.0));
    const Stencil x1 = triangle_with(Vector3d(0.5, 0.3, 0.0));
    CHECK(checked_step(x0, x1, false) < 0.5);
  }
  SECTION("alongside an edge, never closer") {
    const Stencil x0 = triangle_with(Vector3d(0.2, -0.1, 0.0));
    const Stencil x1 = triangle_with(Vector3d(0.8, -0.1, 0.0));
    CHECK(checked_step(x0, x1, false) == 1.0);
  }
  SECTION("coplanar edges crossing") {
    const Stencil x0{Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0.5, 0.5, 0),
                     Vector3d(0.5, 1.5, 0)};
    Stencil x1 = x0;
    x1[2].y() -= 1.0;
    x1[3].y() -= 1.0;
    CHECK(checked_step(x0, x1, true) < 0.5);
  }
}

TEST_CASE("CCD: tiny starting distance, zero motion, receding", "[ccd]") {
  const Stencil near = triangle_with(Vector3d(0.25, 0.25, 1e-9));
  SECTION("approaching from 1e-9") {
    const double step = checked_step(near, triangle_with(Vector3d(0.25, 0.25, -1.0)), false);
    CHECK(step < 1e-9);
    CHECK(step > 0.0);
  }
  SECTION("zero motion") { CHECK(gr::point_triangle_ccd(near, near, {}) == 1.0); }
  SECTION("receding") {
    CHECK(checked_step(near, triangle_with(Vector3d(0.25, 0.25, 1.0)), false) == 1.0);
  }
  SECTION("touching and moving") {
    const Stencil touching = triangle_with(Vector3d(0.25, 0.25, 0.0));
    CHECK(gr::point_triangle_ccd(touching, triangle_with(Vector3d(0.25, 0.25, 1.0)), {}) == 0.0);
  }
  SECTION("below the absolute floor") {
    gr::CcdOptions options;
    options.min_separation = 1e-6;
    CHECK(gr::point_triangle_ccd(near, triangle_with(Vector3d(0.25, 0.25, -1.0)), options) == 0.0);
    CHECK(checked_step(near, triangle_with(Vector3d(0.25, 0.25, 1.0)), false, options) == 1.0);
  }
}

TEST_CASE("CCD: a rotating triangle approximated by linear motion", "[ccd]") {
  // The triangle turns by `angle` about the z axis through its corner; each corner moves
  // on its chord. A point sits just above the far corner's chord, midway.
  const double angle = GENERATE(0.5, 1.5, 3.0);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(angle, Vector3d::UnitZ()).toRotationMatrix();
  const Vector3d far(1, 0, 0), other(0.5, 0.3, 0);
  const Vector3d p = 0.5 * (far + R * far) + Vector3d(0, 0, 0.001);
  const Stencil x0{p, Vector3d(0, 0, 0), far, other};
  const Stencil x1{p, Vector3d(0, 0, 0), R * far, R * other};
  CAPTURE(angle);
  CHECK(checked_step(x0, x1, false) < 0.5);
}

TEST_CASE("CCD: both sides moving", "[ccd]") {
  const Stencil x0{Vector3d(0.3, 0.3, 0.5), Vector3d(0, 0, -0.5), Vector3d(1, 0, -0.5),
                   Vector3d(0, 1, -0.5)};
  Stencil x1 = x0;
  x1[0].z() -= 2.0;
  for (int i = 1; i < 4; ++i) x1[i] += Vector3d(0.1, -0.2, 2.0);
  const double step = checked_step(x0, x1, false);
  CHECK(step < 0.25);  // they meet at a quarter of the motion
  CHECK(step > 0.2);
  const Stencil e0{Vector3d(-1, 0, 0.5), Vector3d(1, 0, 0.5), Vector3d(0, -1, -0.5),
                   Vector3d(0, 1, -0.5)};
  Stencil e1 = e0;
  e1[0].z() -= 1.0;
  e1[1].z() -= 1.0;
  e1[2].z() += 1.0;
  e1[3].z() += 1.0;
  CHECK(checked_step(e0, e1, true) < 0.5);
}

TEST_CASE("CCD: degenerate elements", "[ccd]") {
  SECTION("collinear triangle") {
    const Stencil x0{Vector3d(0.5, 0.5, 0), Vector3d(0, 0, 0), Vector3d(1, 0, 0),
                     Vector3d(2, 0, 0)};
    Stencil x1 = x0;
    x1[0].y() = -0.5;
    CHECK(checked_step(x0, x1, false) < 0.5);
  }
  SECTION("zero-length edge") {
    const Stencil x0{Vector3d(0.5, 0.5, 0), Vector3d(0.5, 0.5, 0), Vector3d(0, 0, 0),
                     Vector3d(1, 0, 0)};
    Stencil x1 = x0;
    x1[0].y() = x1[1].y() = -0.5;
    CHECK(checked_step(x0, x1, true) < 0.5);
  }
}

TEST_CASE("CCD: an exhausted budget returns a smaller step, never a larger one", "[ccd]") {
  // A grazing approach: the distance shrinks slowly against the bound, so many small
  // advances are needed.
  const Stencil x0 = triangle_with(Vector3d(-0.5, 0.3, 0.01));
  const Stencil x1 = triangle_with(Vector3d(1.5, 0.3, -0.001));
  const double full = checked_step(x0, x1, false);
  for (const int budget : {1, 2, 5, 20}) {
    gr::CcdOptions options;
    options.max_iterations = budget;
    const double limited = checked_step(x0, x1, false, options);
    CAPTURE(budget);
    CHECK(limited <= full);
  }
}

TEST_CASE("max_step takes the minimum over the candidates", "[ccd]") {
  gr::MatrixX3d V0(8, 3), V1;
  V0 << 0.25, 0.25, 1.0, 0, 0, 0, 1, 0, 0, 0, 1, 0,  // point above a triangle
      0, 0, 2, 1, 0, 2, 0.5, -0.5, 3, 0.5, 0.5, 3;   // two crossing edges
  V1 = V0;
  V1(0, 2) = -1.0;                      // reaches the triangle at 0.5
  V1.row(6).z() = V1.row(7).z() = 1.0;  // reaches edge a at 0.5 too, but later with separation
  V1.row(6).z() = 2.8;
  V1.row(7).z() = 2.8;
  gr::Candidates c;
  c.point_triangle.push_back({0, {1, 2, 3}});
  c.edge_edge.push_back({{4, 5}, {6, 7}});
  const double both = gr::max_step(c, V0, V1);
  CHECK(both < 0.5);
  CHECK(both > 0.4);
  gr::Candidates only_edges;
  only_edges.edge_edge = c.edge_edge;
  CHECK(gr::max_step(only_edges, V0, V1) == 1.0);
  CHECK(gr::max_step(gr::Candidates{}, V0, V1) == 1.0);
  gr::CcdOptions bad;
  bad.min_separation_ratio = 1.0;
  CHECK_THROWS_AS(gr::max_step(c, V0, V1, bad), std::invalid_argument);
}

TEST_CASE("vertex_steps bounds each vertex by the pairs it belongs to", "[ccd]") {
  gr::MatrixX3d V0(8, 3), V1;
  V0 << 0.25, 0.25, 1.0, 0, 0, 0, 1, 0, 0, 0, 1, 0,  // point above a triangle
      0, 0, 2, 1, 0, 2, 0.5, -0.5, 3, 0.5, 0.5, 3;   // two crossing edges, kept apart
  V1 = V0;
  V1(0, 2) = -1.0;  // reaches the triangle at 0.5
  V1.row(6).z() = 2.8;
  V1.row(7).z() = 2.8;
  gr::Candidates c;
  c.point_triangle.push_back({0, {1, 2, 3}});
  c.edge_edge.push_back({{4, 5}, {6, 7}});
  const std::vector<double> steps = gr::vertex_steps(c, V0, V1);
  REQUIRE(steps.size() == 8);
  const double whole = gr::max_step(c, V0, V1);
  for (int v = 0; v < 4; ++v) CHECK(steps[static_cast<std::size_t>(v)] == whole);
  for (int v = 4; v < 8; ++v) CHECK(steps[static_cast<std::size_t>(v)] == 1.0);
  CHECK(*std::min_element(steps.begin(), steps.end()) == whole);
  gr::CcdOptions bad;
  bad.max_iterations = 0;
  CHECK_THROWS_AS(gr::vertex_steps(c, V0, V1, bad), std::invalid_argument);
}
