#pragma once

#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include "core/common/types.hpp"
#include "core/energies/energy_term.hpp"
#include "core/finite_difference.hpp"

namespace gr::test {

/// Vertex-major flattening (x0 y0 z0 x1 ...) of #V×3 positions, and back.
inline Eigen::VectorXd flatten(const MatrixX3d& V) {
  return Eigen::Map<const Eigen::VectorXd>(V.data(), V.size());
}
inline MatrixX3d unflatten(const Eigen::VectorXd& x) {
  return Eigen::Map<const MatrixX3d>(x.data(), x.size() / 3, 3);
}

/// Checks a term of garment positions alone (t fixed, so x holds the vertices only) at x
/// (3#V, vertex-major): positive there, gradient and exact Hessian against central
/// differences, and the projected Hessian positive semi-definite.
inline void check_position_energy(const EnergyTerm& energy, const Eigen::VectorXd& x,
                                  double tolerance, double t = 1.0) {
  const auto f = [&](const Eigen::VectorXd& y) { return energy.value(unflatten(y), t); };
  const auto grad = [&](const Eigen::VectorXd& y) {
    Eigen::VectorXd g;
    energy.gradient(unflatten(y), t, g);
    return g;
  };
  Eigen::VectorXd g;
  energy.gradient(unflatten(x), t, g);
  CHECK(f(x) > 0.0);
  CHECK(fd_matches(g, fd_gradient(f, x), tolerance));
  const Eigen::MatrixXd H = energy.hessian(unflatten(x), t, false);
  CHECK(fd_matches(H, fd_hessian(grad, x), tolerance));
  const Eigen::MatrixXd P = energy.hessian(unflatten(x), t, true);
  CHECK(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(P).eigenvalues().minCoeff() >=
        -1e-12 * P.norm());
}

}  // namespace gr::test
