#pragma once

#include <algorithm>

#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include "core/common/types.hpp"

namespace gr::test {

/// Central-difference gradient of a scalar function f(x).
template <typename Function>
Eigen::VectorXd fd_gradient(Function f, const Eigen::VectorXd& x, double h = 1e-6) {
  Eigen::VectorXd g(x.size()), xp = x, xm = x;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    xp[i] = x[i] + h;
    xm[i] = x[i] - h;
    g[i] = (f(xp) - f(xm)) / (2.0 * h);
    xp[i] = xm[i] = x[i];
  }
  return g;
}

/// Central-difference Jacobian of a vector function f(x) (the Hessian when f is a gradient).
template <typename Function>
Eigen::MatrixXd fd_jacobian(Function f, const Eigen::VectorXd& x, double h = 1e-6) {
  Eigen::VectorXd xp = x, xm = x;
  Eigen::MatrixXd J;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    xp[i] = x[i] + h;
    xm[i] = x[i] - h;
    const Eigen::VectorXd column = (f(xp) - f(xm)) / (2.0 * h);
    if (i == 0) J.resize(column.size(), x.size());
    J.col(i) = column;
    xp[i] = xm[i] = x[i];
  }
  return J;
}

/// ||a - b|| relative to max(||a||, ||b||, floor).
inline double relative_error(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, double floor = 1e-10) {
  return (a - b).norm() / std::max({a.norm(), b.norm(), floor});
}

/// Vertex-major flattening (x0 y0 z0 x1 ...) of #V×3 positions, and back.
inline Eigen::VectorXd flatten(const MatrixX3d& V) {
  return Eigen::Map<const Eigen::VectorXd>(V.data(), V.size());
}
inline MatrixX3d unflatten(const Eigen::VectorXd& x) {
  return Eigen::Map<const MatrixX3d>(x.data(), x.size() / 3, 3);
}

/// Checks an energy of garment positions (value(V), gradient(V, g), hessian(V, project))
/// at x (3#V, vertex-major): gradient and exact Hessian against central differences, the
/// returned value against value(), and the projected Hessian positive semi-definite.
template <typename Energy>
void check_position_energy(const Energy& energy, const Eigen::VectorXd& x, double tolerance) {
  const auto f = [&](const Eigen::VectorXd& y) { return energy.value(unflatten(y)); };
  const auto grad = [&](const Eigen::VectorXd& y) {
    Eigen::VectorXd g;
    energy.gradient(unflatten(y), g);
    return g;
  };
  Eigen::VectorXd g;
  const double value = energy.gradient(unflatten(x), g);
  CHECK(value == Approx(f(x)).epsilon(1e-12));
  CHECK(value > 0.0);
  CHECK(relative_error(g, fd_gradient(f, x)) < tolerance);
  const Eigen::MatrixXd H = energy.hessian(unflatten(x), false);
  CHECK(relative_error(H, fd_jacobian(grad, x)) < tolerance);
  const Eigen::MatrixXd P = energy.hessian(unflatten(x), true);
  CHECK(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(P).eigenvalues().minCoeff() >= -1e-12 * P.norm());
}

}  // namespace gr::test
