#include <catch2/catch.hpp>

#include "core/distance/distance_test_support.hpp"
#include "core/distance/point_edge_distance.hpp"

using gr::PointEdgeDistanceType;
using gr::Vector3d;

namespace {

void check_point_edge(const std::array<Vector3d, 3>& x) {
  const PointEdgeDistanceType type = gr::point_edge_distance_type(x[0], x[1], x[2]);
  CAPTURE(static_cast<int>(type));
  // The classified distance is the minimum: no sample of the segment is closer, and the
  // samples get within their spacing.
  const double d_sq = gr::point_edge_distance_sq(x[0], x[1], x[2]);
  const double sampled = gr::test::sampled_distance_sq(
      [&](double, double) { return x[0]; }, 0,
      [&](double s, double) -> Vector3d { return x[1] + s * (x[2] - x[1]); }, 1, 2000);
  CHECK(d_sq <= sampled + 1e-15);
  CHECK(std::sqrt(d_sq) >= std::sqrt(sampled) - 1e-3);

  const auto value = [type](const Eigen::VectorXd& v) {
    const auto y = gr::test::unstack<3>(v);
    return gr::point_edge_distance_sq(y[0], y[1], y[2], type);
  };
  const auto gradient = [type](const Eigen::VectorXd& v) -> Eigen::VectorXd {
    const auto y = gr::test::unstack<3>(v);
    return gr::point_edge_distance_sq_gradient(y[0], y[1], y[2], type);
  };
  const auto hessian = [type](const Eigen::VectorXd& v) -> Eigen::MatrixXd {
    const auto y = gr::test::unstack<3>(v);
    return gr::point_edge_distance_sq_hessian(y[0], y[1], y[2], type);
  };
  gr::test::check_derivatives(value, gradient, hessian, gr::test::stack(x));
}

}  // namespace

TEST_CASE("point-edge distance in every closest-feature region", "[distance][grad]") {
  const double offset = GENERATE(0.0, 1e-12, -1e-12);
  const unsigned seed = GENERATE(11u, 12u);
  const Eigen::Matrix3d R = gr::test::random_rotation(seed);
  const Vector3d shift(0.3, -0.2, 0.1);
  const Vector3d e0(0, 0, 0), e1(1, 0, 0);
  CAPTURE(offset, seed);

  Vector3d p;
  PointEdgeDistanceType expected = PointEdgeDistanceType::P_E;
  SECTION("endpoint e0") {
    p = Vector3d(-0.5, 0.3, 0.2);
    expected = PointEdgeDistanceType::P_E0;
  }
  SECTION("endpoint e1") {
    p = Vector3d(1.5, -0.3, 0.2);
    expected = PointEdgeDistanceType::P_E1;
  }
  SECTION("interior") { p = Vector3d(0.4, 0.3, -0.2); }
  SECTION("interior, on the line") { p = Vector3d(0.4, offset, -offset); }
  SECTION("nearly coincident with e0") {
    p = Vector3d(-1e-9, offset, 0.0);
    expected = PointEdgeDistanceType::P_E0;
  }
  const auto x = gr::test::moved<3>({p, e0, e1}, R, shift);
  CHECK(gr::point_edge_distance_type(x[0], x[1], x[2]) == expected);
  check_point_edge(x);
}

TEST_CASE("point-edge distance on region boundaries", "[distance][grad]") {
  const double offset = GENERATE(0.0, 1e-12, -1e-12);
  const double along = GENERATE(0.0, 1.0);
  const auto x =
      gr::test::moved<3>({Vector3d(along + offset, 0.4, 0.1), Vector3d(0, 0, 0), Vector3d(1, 0, 0)},
                         gr::test::random_rotation(5), Vector3d(0.1, 0.2, 0.3));
  CAPTURE(offset, along);
  check_point_edge(x);
}

TEST_CASE("point against a zero-length edge is the point-point case", "[distance]") {
  const Vector3d p(0.3, 0.4, 0.0), e(0.1, 0.1, 0.1);
  CHECK(gr::point_edge_distance_type(p, e, e) == PointEdgeDistanceType::P_E0);
  CHECK(gr::point_edge_distance_sq(p, e, e) == Approx((p - e).squaredNorm()));
}
