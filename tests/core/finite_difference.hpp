#pragma once

#include <algorithm>

#include <Eigen/Core>

namespace gr::test {

/// Central-difference gradient of a scalar function f(x) with step h.
template <typename Function>
Eigen::VectorXd fd_gradient(const Function& f, const Eigen::VectorXd& x, double h = 1e-6) {
  Eigen::VectorXd g(x.size());
  Eigen::VectorXd y = x;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    y[i] = x[i] + h;
    const double plus = f(y);
    y[i] = x[i] - h;
    const double minus = f(y);
    y[i] = x[i];
    g[i] = (plus - minus) / (2.0 * h);
  }
  return g;
}

/// Central-difference Hessian from a gradient function grad(x) (column i is the
/// difference of gradients along x_i), symmetrized.
template <typename Gradient>
Eigen::MatrixXd fd_hessian(const Gradient& grad, const Eigen::VectorXd& x, double h = 1e-6) {
  Eigen::MatrixXd H(x.size(), x.size());
  Eigen::VectorXd y = x;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    y[i] = x[i] + h;
    const Eigen::VectorXd plus = grad(y);
    y[i] = x[i] - h;
    const Eigen::VectorXd minus = grad(y);
    y[i] = x[i];
    H.col(i) = (plus - minus) / (2.0 * h);
  }
  return 0.5 * (H + H.transpose());
}

/// True when an analytic derivative matches its finite-difference estimate to `tolerance`
/// relative to the larger of the two (or to `floor`, for derivatives that vanish).
inline bool fd_matches(const Eigen::MatrixXd& analytic, const Eigen::MatrixXd& estimate,
                       double tolerance = 1e-6, double floor = 1e-12) {
  const double scale = std::max({analytic.norm(), estimate.norm(), floor});
  return (analytic - estimate).norm() <= tolerance * scale;
}

}  // namespace gr::test
