#include <algorithm>
#include <cmath>

#include <catch2/catch.hpp>

#include "core/barrier/barrier.hpp"
#include "core/finite_difference.hpp"

TEST_CASE("barrier vanishes flatly at dhat and is positive inside", "[barrier]") {
  const double dhat = 0.002, xhat = dhat * dhat;
  CHECK(gr::barrier(xhat, xhat) == 0.0);
  CHECK(gr::barrier(2 * xhat, xhat) == 0.0);
  CHECK(gr::barrier_first_derivative(xhat, xhat) == 0.0);
  CHECK(gr::barrier_second_derivative(xhat, xhat) == 0.0);
  // Value, slope and curvature approach zero from inside (C2 at dhat).
  const double near = xhat * (1 - 1e-6);
  CHECK(gr::barrier(near, xhat) > 0.0);
  CHECK(std::abs(gr::barrier_first_derivative(near, xhat)) < 1e-11 * xhat);
  CHECK(std::abs(gr::barrier_second_derivative(near, xhat)) < 1e-5);
  double previous = 0.0;
  for (double x = 0.9 * xhat; x > 1e-30; x *= 0.1) {
    const double b = gr::barrier(x, xhat);
    CHECK(b > previous);
    CHECK(gr::barrier_first_derivative(x, xhat) < 0.0);
    CHECK(gr::barrier_second_derivative(x, xhat) > 0.0);
    previous = b;
  }
  // Grows without bound: like xhat² ln(xhat / x) as x → 0.
  CHECK(gr::barrier(1e-300, xhat) > 600 * xhat * xhat);
  CHECK(std::isinf(gr::barrier(0.0, xhat)));
}

TEST_CASE("barrier derivatives match finite differences", "[barrier][grad]") {
  const double xhat = GENERATE(1.0, 4e-6);
  const double fraction = GENERATE(1e-6, 1e-3, 0.1, 0.5, 0.9, 0.999);
  const double x = fraction * xhat;
  const double h = 1e-3 * std::min(x, xhat - x);  // stays inside (0, xhat)
  CAPTURE(xhat, fraction);
  const auto value = [xhat](const Eigen::VectorXd& v) { return gr::barrier(v[0], xhat); };
  const auto first = [xhat](const Eigen::VectorXd& v) {
    return Eigen::VectorXd::Constant(1, gr::barrier_first_derivative(v[0], xhat)).eval();
  };
  const Eigen::VectorXd at = Eigen::VectorXd::Constant(1, x);
  CHECK(gr::test::fd_matches(first(at), gr::test::fd_gradient(value, at, h), 1e-6));
  CHECK(
      gr::test::fd_matches(Eigen::MatrixXd::Constant(1, 1, gr::barrier_second_derivative(x, xhat)),
                           gr::test::fd_hessian(first, at, h), 1e-6));
}
