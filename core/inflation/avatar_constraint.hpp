#pragma once

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

}  // namespace gr
