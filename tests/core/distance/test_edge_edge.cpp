#include <catch2/catch.hpp>

#include "core/distance/distance_test_support.hpp"
#include "core/distance/edge_edge_distance.hpp"

using gr::EdgeEdgeDistanceType;
using gr::Vector3d;

namespace {

void check_edge_edge(const std::array<Vector3d, 4>& x) {
  const EdgeEdgeDistanceType type = gr::edge_edge_distance_type(x[0], x[1], x[2], x[3]);
  CAPTURE(static_cast<int>(type));
  const double d_sq = gr::edge_edge_distance_sq(x[0], x[1], x[2], x[3]);
  const int samples = 1000;
  const double sampled = gr::test::sampled_distance_sq(
      [&](double s, double) -> Vector3d { return x[0] + s * (x[1] - x[0]); }, 1,
      [&](double s, double) -> Vector3d { return x[2] + s * (x[3] - x[2]); }, 1, samples);
  CHECK(d_sq <= sampled + 1e-15);
  CHECK(std::sqrt(d_sq) >= std::sqrt(sampled) - 4.0 / samples);

  const auto value = [type](const Eigen::VectorXd& v) {
    const auto y = gr::test::unstack<4>(v);
    return gr::edge_edge_distance_sq(y[0], y[1], y[2], y[3], type);
  };
  const auto gradient = [type](const Eigen::VectorXd& v) -> Eigen::VectorXd {
    const auto y = gr::test::unstack<4>(v);
    return gr::edge_edge_distance_sq_gradient(y[0], y[1], y[2], y[3], type);
  };
  const auto hessian = [type](const Eigen::VectorXd& v) -> Eigen::MatrixXd {
    const auto y = gr::test::unstack<4>(v);
    return gr::edge_edge_distance_sq_hessian(y[0], y[1], y[2], y[3], type);
  };
  gr::test::check_derivatives(value, gradient, hessian, gr::test::stack(x));
}

}  // namespace

TEST_CASE("edge-edge distance in every closest-feature region", "[distance][grad]") {
  using T = EdgeEdgeDistanceType;
  const double offset = GENERATE(0.0, 1e-12, -1e-12);
  const unsigned seed = GENERATE(31u, 32u);
  const Vector3d ea0(-1, 0, 0), ea1(1, 0, 0);
  const double h = 0.3;
  CAPTURE(offset, seed);

  Vector3d eb0, eb1;
  T expected = T::EA_EB;
  SECTION("interiors") {
    eb0 = Vector3d(0, -1, h);
    eb1 = Vector3d(0.2, 1, h);
  }
  SECTION("interiors, crossing") {
    eb0 = Vector3d(0, -1, offset);
    eb1 = Vector3d(0.2, 1, offset);
  }
  SECTION("ea0 against b") {
    eb0 = Vector3d(-1.5, -1, h);
    eb1 = Vector3d(-1.4, 1, h);
    expected = T::EA0_EB;
  }
  SECTION("ea1 against b") {
    eb0 = Vector3d(1.5, -1, h);
    eb1 = Vector3d(1.4, 1, h);
    expected = T::EA1_EB;
  }
  SECTION("eb0 against a") {
    eb0 = Vector3d(0.2, 0.5, h);
    eb1 = Vector3d(0.3, 2, h);
    expected = T::EA_EB0;
  }
  SECTION("eb1 against a") {
    eb0 = Vector3d(0.3, 2, h);
    eb1 = Vector3d(0.2, 0.5, h);
    expected = T::EA_EB1;
  }
  SECTION("ea0 eb0") {
    eb0 = Vector3d(-1.5, -0.5, h);
    eb1 = Vector3d(-1.6, -2, h);
    expected = T::EA0_EB0;
  }
  SECTION("ea0 eb1") {
    eb0 = Vector3d(-1.6, -2, h);
    eb1 = Vector3d(-1.5, -0.5, h);
    expected = T::EA0_EB1;
  }
  SECTION("ea1 eb0") {
    eb0 = Vector3d(1.5, 0.5, h);
    eb1 = Vector3d(1.6, 2, h);
    expected = T::EA1_EB0;
  }
  SECTION("ea1 eb1") {
    eb0 = Vector3d(1.6, 2, h);
    eb1 = Vector3d(1.5, 0.5, h);
    expected = T::EA1_EB1;
  }
  SECTION("nearly coincident endpoints") {
    eb0 = Vector3d(1 + 1e-9, offset, 0);
    eb1 = Vector3d(1.6, 2, h);
    expected = T::EA1_EB0;
  }
  const auto x = gr::test::moved<4>({ea0, ea1, eb0, eb1}, gr::test::random_rotation(seed),
                                    Vector3d(0.1, -0.2, 0.3));
  CHECK(gr::edge_edge_distance_type(x[0], x[1], x[2], x[3]) == expected);
  check_edge_edge(x);
}

TEST_CASE("nearly parallel edges never use the line-line case", "[distance][grad]") {
  const double angle = GENERATE(0.0, 1e-10, -1e-10);
  const double height = GENERATE(0.3, 1e-12, 0.0);
  const double start = GENERATE(-0.5, -1.5, 0.999);
  const Vector3d direction(std::cos(angle), std::sin(angle), 0.0);
  const Vector3d eb0(start, 0.0, height);
  const auto x =
      gr::test::moved<4>({Vector3d(-1, 0, 0), Vector3d(1, 0, 0), eb0, eb0 + 1.2 * direction},
                         gr::test::random_rotation(41), Vector3d(0.2, 0.2, 0.2));
  CAPTURE(angle, height, start);
  CHECK(gr::edge_edge_distance_type(x[0], x[1], x[2], x[3]) != EdgeEdgeDistanceType::EA_EB);
  check_edge_edge(x);
}
