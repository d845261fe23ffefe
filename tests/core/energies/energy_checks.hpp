#pragma once

#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include "core/common/types.hpp"
#include "core/energies/dof_layout.hpp"
#include "core/energies/energy_term.hpp"
#include "core/energies/stencil_term.hpp"
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

/// Checks a term over the unknowns of `layout` (t included when it is free) at x
/// (layout.dof_count()): positive there, gradient and exact Hessian against central
/// differences, to `gradient_tolerance` and `hessian_tolerance`.
inline void check_energy_in_layout(const EnergyTerm& energy, const DofLayout& layout,
                                   const Eigen::VectorXd& x, double gradient_tolerance,
                                   double hessian_tolerance) {
  const auto f = [&](const Eigen::VectorXd& y) {
    return energy.value(layout.garment(y), layout.t(y));
  };
  const auto grad = [&](const Eigen::VectorXd& y) {
    Eigen::VectorXd g;
    energy.gradient(layout.garment(y), layout.t(y), g);
    return g;
  };
  Eigen::VectorXd g;
  energy.gradient(layout.garment(x), layout.t(x), g);
  REQUIRE(g.size() == layout.dof_count());
  CHECK(f(x) > 0.0);
  CHECK(fd_matches(g, fd_gradient(f, x), gradient_tolerance));
  const Eigen::MatrixXd H = energy.hessian(layout.garment(x), layout.t(x), false);
  CHECK(fd_matches(H, fd_hessian(grad, x), hessian_tolerance));
}

/// Checks a stencil term's local pieces (Term::element_*, see StencilTerm) on one element at
/// local coordinates q: the gradient's returned value is the value, gradient and exact
/// Hessian match central differences, the Hessian is symmetric, and with a closed-form
/// projection the projected block is positive semi-definite. Derivatives smaller than
/// `floor` (an element at rest has a zero gradient) are compared to tolerance × floor,
/// since central differences do not resolve them further.
template <typename Term>
void check_element_derivatives(const typename Term::Element& element,
                               const typename Term::LocalVector& q, double tolerance,
                               double floor = 1e-6) {
  using Local = typename Term::LocalVector;
  using LocalMatrix = typename Term::LocalMatrix;
  const auto f = [&](const Eigen::VectorXd& y) { return Term::element_value(element, Local(y)); };
  const auto grad = [&](const Eigen::VectorXd& y) {
    Local g = Local::Zero();
    Term::element_gradient(element, Local(y), g);
    return Eigen::VectorXd(g);
  };
  Local g = Local::Zero();
  CHECK(Term::element_gradient(element, q, g) == Approx(Term::element_value(element, q)));
  CHECK(fd_matches(g, fd_gradient(f, q), tolerance, floor));
  LocalMatrix h = LocalMatrix::Zero();
  Term::element_hessian(element, q, false, h);
  CHECK(fd_matches(h, fd_hessian(grad, q), tolerance, floor));
  CHECK((h - h.transpose()).norm() <= 1e-12 * h.norm());
  if (Term::kProjection == HessianProjection::closed_form) {
    LocalMatrix p = LocalMatrix::Zero();
    Term::element_hessian(element, q, true, p);
    CHECK(Eigen::SelfAdjointEigenSolver<LocalMatrix>(p).eigenvalues().minCoeff() >=
          -1e-12 * p.norm());
  }
}

}  // namespace gr::test
