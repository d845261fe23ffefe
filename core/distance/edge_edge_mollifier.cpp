#include "core/distance/edge_edge_mollifier.hpp"

#include "core/distance/distance_forms.hpp"

namespace gr {

double edge_edge_mollifier_threshold(const Vector3d& ea0_rest, const Vector3d& ea1_rest,
                                     const Vector3d& eb0_rest, const Vector3d& eb1_rest) {
  return 1e-3 * (ea1_rest - ea0_rest).squaredNorm() * (eb1_rest - eb0_rest).squaredNorm();
}

double mollifier(double x, double eps) {
  if (x >= eps) return 1.0;
  const double r = x / eps;
  return (2.0 - r) * r;
}

double mollifier_first_derivative(double x, double eps) {
  if (x >= eps) return 0.0;
  return 2.0 / eps * (1.0 - x / eps);
}

double mollifier_second_derivative(double x, double eps) {
  if (x >= eps) return 0.0;
  return -2.0 / (eps * eps);
}

double edge_edge_mollifier(const Vector3d& ea0, const Vector3d& ea1, const Vector3d& eb0,
                           const Vector3d& eb1, double eps, Vector12d* gradient,
                           Matrix12d* hessian) {
  const bool derivatives = gradient || hessian;
  Vector6d gc;
  Matrix6d Hc;
  const double c =
      cross_sq_form(ea1 - ea0, eb1 - eb0, derivatives ? &gc : nullptr, hessian ? &Hc : nullptr);
  if (!derivatives) return mollifier(c, eps);
  // The cross product's arguments are the differences ea1 - ea0 and eb1 - eb0.
  const std::array<VertexDifference, 2> diffs{VertexDifference{1, 0}, VertexDifference{3, 2}};
  const double dm = mollifier_first_derivative(c, eps);
  const Vector12d grad_c = pull_back_gradient<4, 2>(gc, diffs);
  if (gradient) *gradient = dm * grad_c;
  if (hessian) {
    *hessian = mollifier_second_derivative(c, eps) * grad_c * grad_c.transpose() +
               dm * pull_back_hessian<4, 2>(Hc, diffs);
  }
  return mollifier(c, eps);
}

}  // namespace gr
