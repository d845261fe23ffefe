#pragma once

#include "core/energies/dof_layout.hpp"
#include "core/energies/energy_term.hpp"

namespace gr {

/// The augmented Lagrangian on the constraint t = 1, written on the avatar's vertices: the
/// residual A(t) - A = (t - 1)(A - A0), with S = sum_i |A_i - A0_i|^2,
///   value(t) = 1/2 lambda1 (1 - t)^2 S + lambda2 (1 - t) S.
/// This is the vector AL (penalty 1/2 lambda1 |c|^2, multiplier term -lambda2_vec·c,
/// c = A(t) - A) with the multiplier kept along A - A0 (lambda2_vec = lambda2 (A - A0)),
/// so the update lambda2_vec -= lambda1 c is Algorithm 1's lambda2 += lambda1 (1 - t); a
/// positive lambda2 lowers the energy as t grows, pushing t towards 1.
struct AvatarConstraint {
  double displacement_sq = 0.0;  ///< S, normalized units squared
  double lambda1 = 1.0;
  double lambda2 = 0.0;

  double value(double t) const {
    return (0.5 * lambda1 * (1.0 - t) * (1.0 - t) + lambda2 * (1.0 - t)) * displacement_sq;
  }
  double derivative(double t) const { return -(lambda1 * (1.0 - t) + lambda2) * displacement_sq; }
  double second_derivative() const { return lambda1 * displacement_sq; }
  /// Algorithm 1, line 17.
  void update_multiplier(double t) { lambda2 += lambda1 * (1.0 - t); }
};

/// The augmented Lagrangian as a term of the inflation's objective (weight 1): it depends on
/// t alone, so its gradient and Hessian have one entry, at t. Reads `constraint`, which the
/// augmented-Lagrangian loop updates between solves and which must outlive the term.
/// @pre layout.t_free.
class AvatarConstraintTerm : public EnergyTerm {
 public:
  AvatarConstraintTerm(const AvatarConstraint& constraint, const DofLayout& layout)
      : layout_(layout), constraint_(constraint) {
    hessian_.resize(layout.dof_count(), layout.dof_count());
    hessian_.insert(layout.t_index(), layout.t_index()) = 0.0;
    hessian_.makeCompressed();
  }

  const char* name() const override { return "augmented_lagrangian"; }
  double value(const Eigen::Ref<const MatrixX3d>&, double t) const override {
    return constraint_.value(t);
  }
  void gradient(const Eigen::Ref<const MatrixX3d>&, double t,
                Eigen::VectorXd& gradient) const override {
    gradient.setZero(layout_.dof_count());
    gradient[layout_.t_index()] = constraint_.derivative(t);
  }
  /// Convex in t, so the same with or without projection.
  const Eigen::SparseMatrix<double>& hessian(const Eigen::Ref<const MatrixX3d>&, double,
                                             bool) const override {
    hessian_.valuePtr()[0] = constraint_.second_derivative();
    return hessian_;
  }

 private:
  DofLayout layout_;
  const AvatarConstraint& constraint_;
  mutable Eigen::SparseMatrix<double> hessian_;
};

}  // namespace gr
