#include <catch2/catch.hpp>

#include "core/distance/distance_test_support.hpp"
#include "core/distance/point_triangle_distance.hpp"

using gr::PointTriangleDistanceType;
using gr::Vector3d;

namespace {

void check_point_triangle(const std::array<Vector3d, 4>& x) {
  const PointTriangleDistanceType type = gr::point_triangle_distance_type(x[0], x[1], x[2], x[3]);
  CAPTURE(static_cast<int>(type));
  const double d_sq = gr::point_triangle_distance_sq(x[0], x[1], x[2], x[3]);
  const int samples = 200;
  const double sampled = gr::test::sampled_distance_sq(
      [&](double, double) { return x[0]; }, 0,
      [&](double s, double t) -> Vector3d { return x[1] + s * (x[2] - x[1]) + t * (x[3] - x[1]); },
      2, samples);
  CHECK(d_sq <= sampled + 1e-15);
  CHECK(std::sqrt(d_sq) >= std::sqrt(sampled) - 4.0 / samples);

  const auto value = [type](const Eigen::VectorXd& v) {
    const auto y = gr::test::unstack<4>(v);
    return gr::point_triangle_distance_sq(y[0], y[1], y[2], y[3], type);
  };
  const auto gradient = [type](const Eigen::VectorXd& v) -> Eigen::VectorXd {
    const auto y = gr::test::unstack<4>(v);
    return gr::point_triangle_distance_sq_gradient(y[0], y[1], y[2], y[3], type);
  };
  const auto hessian = [type](const Eigen::VectorXd& v) -> Eigen::MatrixXd {
    const auto y = gr::test::unstack<4>(v);
    return gr::point_triangle_distance_sq_hessian(y[0], y[1], y[2], y[3], type);
  };
  gr::test::check_derivatives(value, gradient, hessian, gr::test::stack(x));
}

}  // namespace

TEST_CASE("point-triangle distance in every closest-feature region", "[distance][grad]") {
  using T = PointTriangleDistanceType;
  const double offset = GENERATE(0.0, 1e-12, -1e-12);
  const unsigned seed = GENERATE(21u, 22u);
  const Vector3d t0(0, 0, 0), t1(1, 0, 0), t2(0, 1, 0);
  CAPTURE(offset, seed);

  Vector3d p;
  T expected = T::P_T;
  SECTION("interior") { p = Vector3d(0.25, 0.25, 0.4); }
  SECTION("interior, in the plane") { p = Vector3d(0.25, 0.3, offset); }
  SECTION("edge t0 t1") {
    p = Vector3d(0.5, -0.4, 0.3);
    expected = T::P_E0;
  }
  SECTION("edge t1 t2") {
    p = Vector3d(0.8, 0.8, 0.3);
    expected = T::P_E1;
  }
  SECTION("edge t2 t0") {
    p = Vector3d(-0.4, 0.5, 0.3);
    expected = T::P_E2;
  }
  SECTION("edge t1 t2, in the plane, nearly on it") {
    p = Vector3d(0.5 + 1e-9, 0.5 + 1e-9, offset);
    expected = T::P_E1;
  }
  SECTION("corner t0") {
    p = Vector3d(-0.4, -0.4, 0.3);
    expected = T::P_T0;
  }
  SECTION("corner t1") {
    p = Vector3d(1.5, -0.3, 0.3);
    expected = T::P_T1;
  }
  SECTION("corner t2") {
    p = Vector3d(-0.3, 1.5, -0.3);
    expected = T::P_T2;
  }
  SECTION("nearly coincident with t1") {
    p = Vector3d(1.0 + 1e-9, -1e-9, offset);
    expected = T::P_T1;
  }
  const auto x = gr::test::moved<4>({p, t0, t1, t2}, gr::test::random_rotation(seed),
                                    Vector3d(0.2, 0.1, -0.3));
  CHECK(gr::point_triangle_distance_type(x[0], x[1], x[2], x[3]) == expected);
  check_point_triangle(x);
}

TEST_CASE("point-triangle distance on region boundaries", "[distance][grad]") {
  const double offset = GENERATE(0.0, 1e-12, -1e-12);
  const Vector3d p =
      GENERATE(Vector3d(0.0, 0.5, 0.3), Vector3d(0.5, 0.0, -0.2), Vector3d(0.0, 0.0, 0.3),
               Vector3d(1.0, 0.0, 0.1), Vector3d(0.5, 0.5, 0.2));
  const auto x = gr::test::moved<4>({Vector3d(p.x() + offset, p.y() - offset, p.z()),
                                     Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0)},
                                    gr::test::random_rotation(7), Vector3d(0.1, 0.2, 0.3));
  CAPTURE(offset, p.transpose());
  check_point_triangle(x);
}

TEST_CASE("degenerate triangles are measured as their sides", "[distance][grad]") {
  const double offset = GENERATE(0.0, 1e-12, -1e-12);
  const Vector3d p(0.4, 0.3, 0.2);
  // Collinear corners, and a sliver whose area is below the parallel threshold.
  const Vector3d t2 =
      GENERATE(Vector3d(2.0, 0.0, 0.0), Vector3d(0.5, 1e-10, 0.0), Vector3d(1.0, 0.0, 0.0));
  const auto x = gr::test::moved<4>({p, Vector3d(0, 0, 0), Vector3d(1, 0, offset), t2},
                                    gr::test::random_rotation(9), Vector3d::Zero());
  CAPTURE(offset, t2.transpose());
  CHECK(gr::point_triangle_distance_type(x[0], x[1], x[2], x[3]) != PointTriangleDistanceType::P_T);
  check_point_triangle(x);
}
