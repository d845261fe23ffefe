#include <catch2/catch.hpp>

#include "core/distance/distance_test_support.hpp"
#include "core/distance/edge_edge_mollifier.hpp"

using gr::Vector3d;

TEST_CASE("mollifier is C1 at its threshold and zero for parallel edges", "[distance][mollifier]") {
  const double eps = 0.5;
  CHECK(gr::mollifier(0.0, eps) == 0.0);
  CHECK(gr::mollifier(eps, eps) == 1.0);
  CHECK(gr::mollifier(eps * (1 - 1e-9), eps) == Approx(1.0).margin(1e-12));
  CHECK(gr::mollifier_first_derivative(eps * (1 - 1e-9), eps) == Approx(0.0).margin(1e-8));
  CHECK(gr::mollifier(2 * eps, eps) == 1.0);
  const Vector3d a0(0, 0, 0), a1(1, 0, 0);
  CHECK(gr::edge_edge_mollifier(a0, a1, Vector3d(0, 1, 0), Vector3d(2, 1, 0), 1e-3) == 0.0);
  CHECK(gr::edge_edge_mollifier(a0, a1, Vector3d(0, 1, 0), Vector3d(0, 1, 1), 1e-3) == 1.0);
  CHECK(gr::edge_edge_mollifier_threshold(a0, a1, a0, 2 * a1) == Approx(4e-3));
}

TEST_CASE("edge-edge mollifier derivatives", "[distance][mollifier][grad]") {
  // Angles inside the mollified band (sin² < 1e-3), at its edge, beyond it, and parallel.
  const double angle = GENERATE(0.0, 1e-10, 1e-5, 0.01, 0.02, 0.0316, 0.2);
  const double offset = GENERATE(0.0, 1e-12);
  const std::array<Vector3d, 4> rest{Vector3d(-1, 0, 0), Vector3d(1, 0, 0), Vector3d(-1, 0, 0.1),
                                     Vector3d(1, 0, 0.1)};
  const double eps = gr::edge_edge_mollifier_threshold(rest[0], rest[1], rest[2], rest[3]);
  const Vector3d eb0(-0.5, offset, 0.2);
  const auto x = gr::test::moved<4>({Vector3d(-1, 0, 0), Vector3d(1, 0, 0), eb0,
                                     eb0 + 1.5 * Vector3d(std::cos(angle), std::sin(angle), 0)},
                                    gr::test::random_rotation(51), Vector3d(0.1, 0.1, 0.1));
  CAPTURE(angle, offset);
  const auto value = [eps](const Eigen::VectorXd& v) {
    const auto y = gr::test::unstack<4>(v);
    return gr::edge_edge_mollifier(y[0], y[1], y[2], y[3], eps);
  };
  const auto gradient = [eps](const Eigen::VectorXd& v) -> Eigen::VectorXd {
    const auto y = gr::test::unstack<4>(v);
    gr::Vector12d g;
    gr::edge_edge_mollifier(y[0], y[1], y[2], y[3], eps, &g);
    return g;
  };
  const auto hessian = [eps](const Eigen::VectorXd& v) -> Eigen::MatrixXd {
    const auto y = gr::test::unstack<4>(v);
    gr::Matrix12d H;
    gr::edge_edge_mollifier(y[0], y[1], y[2], y[3], eps, nullptr, &H);
    return H;
  };
  gr::test::check_derivatives(value, gradient, hessian, gr::test::stack(x));
}
