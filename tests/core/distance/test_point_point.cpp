#include <catch2/catch.hpp>

#include "core/distance/distance_test_support.hpp"
#include "core/distance/point_point_distance.hpp"

using gr::Vector3d;

TEST_CASE("point-point distance and derivatives", "[distance][grad]") {
  const double offset = GENERATE(0.0, 1e-12, -1e-12, 0.3);
  const unsigned seed = GENERATE(1u, 2u, 3u);
  const Eigen::Matrix3d R = gr::test::random_rotation(seed);
  const std::array<Vector3d, 2> x{R * Vector3d(0.1, 0.2, 0.3),
                                  R * Vector3d(0.1 + offset, 0.2, 0.3 - offset)};
  CAPTURE(offset, seed);
  CHECK(gr::point_point_distance_sq(x[0], x[1]) == Approx(2.0 * offset * offset).margin(1e-15));
  const auto value = [](const Eigen::VectorXd& v) {
    const auto y = gr::test::unstack<2>(v);
    return gr::point_point_distance_sq(y[0], y[1]);
  };
  const auto gradient = [](const Eigen::VectorXd& v) -> Eigen::VectorXd {
    const auto y = gr::test::unstack<2>(v);
    return gr::point_point_distance_sq_gradient(y[0], y[1]);
  };
  const auto hessian = [](const Eigen::VectorXd& v) -> Eigen::MatrixXd {
    const auto y = gr::test::unstack<2>(v);
    return gr::point_point_distance_sq_hessian(y[0], y[1]);
  };
  gr::test::check_derivatives(value, gradient, hessian, gr::test::stack(x));
}
