#include "core/distance/distance_forms.hpp"

namespace gr {
namespace {

/// [w]×, the matrix of w × (·).
Eigen::Matrix3d cross_matrix(const Vector3d& w) {
  Eigen::Matrix3d m;
  m << 0.0, -w.z(), w.y(), w.z(), 0.0, -w.x(), -w.y(), w.x(), 0.0;
  return m;
}

}  // namespace

double point_point_form(const Vector3d& a, Vector3d* gradient, Eigen::Matrix3d* hessian) {
  if (gradient) *gradient = 2.0 * a;
  if (hessian) *hessian = 2.0 * Eigen::Matrix3d::Identity();
  return a.squaredNorm();
}

double cross_sq_form(const Vector3d& u, const Vector3d& v, Vector6d* gradient, Matrix6d* hessian) {
  const double uu = u.squaredNorm(), vv = v.squaredNorm(), uv = u.dot(v);
  if (gradient) {
    gradient->head<3>() = 2.0 * vv * u - 2.0 * uv * v;
    gradient->tail<3>() = 2.0 * uu * v - 2.0 * uv * u;
  }
  if (hessian) {
    const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
    const Eigen::Matrix3d uv_block =
        4.0 * u * v.transpose() - 2.0 * v * u.transpose() - 2.0 * uv * I;
    hessian->block<3, 3>(0, 0) = 2.0 * vv * I - 2.0 * v * v.transpose();
    hessian->block<3, 3>(3, 3) = 2.0 * uu * I - 2.0 * u * u.transpose();
    hessian->block<3, 3>(0, 3) = uv_block;
    hessian->block<3, 3>(3, 0) = uv_block.transpose();
  }
  return u.cross(v).squaredNorm();
}

double point_line_form(const Vector3d& a, const Vector3d& u, Vector6d* gradient,
                       Matrix6d* hessian) {
  // f = c / q with c = |a × u|² and q = |u|² (q depends on u only).
  const double q = u.squaredNorm();
  Vector6d gc;
  Matrix6d Hc;
  const double c =
      cross_sq_form(a, u, gradient || hessian ? &gc : nullptr, hessian ? &Hc : nullptr);
  const double f = c / q;
  if (!gradient && !hessian) return f;
  Vector6d gq = Vector6d::Zero();
  gq.tail<3>() = 2.0 * u;
  const Vector6d g = (gc - f * gq) / q;
  if (gradient) *gradient = g;
  if (hessian) {
    // d²(c/q) = (Hc - g gq^T - gq g^T - f Hq) / q, with Hq = 2I on the u block.
    *hessian = (Hc - g * gq.transpose() - gq * g.transpose()) / q;
    hessian->block<3, 3>(3, 3) -= (2.0 * f / q) * Eigen::Matrix3d::Identity();
  }
  return f;
}

double point_plane_form(const Vector3d& a, const Vector3d& u, const Vector3d& v, Vector9d* gradient,
                        Matrix9d* hessian) {
  // f = t² / c with the triple product t = a · (u × v) and c = |u × v|².
  const Vector3d n = u.cross(v);
  const double t = a.dot(n);
  Vector6d gc6;
  Matrix6d Hc6;
  const double c =
      cross_sq_form(u, v, gradient || hessian ? &gc6 : nullptr, hessian ? &Hc6 : nullptr);
  const double f = t * t / c;
  if (!gradient && !hessian) return f;
  Vector9d gt;
  gt << n, v.cross(a), a.cross(u);
  Vector9d gc = Vector9d::Zero();
  gc.tail<6>() = gc6;
  // Gradient of f = (2 t gt - f gc) / c.
  const Vector9d g = (2.0 * t * gt - f * gc) / c;
  if (gradient) *gradient = g;
  if (hessian) {
    // The triple product is trilinear: its Hessian has zero diagonal blocks and
    // off-diagonal blocks ±[w]× of the third vector.
    Matrix9d Ht = Matrix9d::Zero();
    Ht.block<3, 3>(0, 3) = -cross_matrix(v);
    Ht.block<3, 3>(0, 6) = cross_matrix(u);
    Ht.block<3, 3>(3, 6) = -cross_matrix(a);
    Ht.block<3, 3>(3, 0) = Ht.block<3, 3>(0, 3).transpose();
    Ht.block<3, 3>(6, 0) = Ht.block<3, 3>(0, 6).transpose();
    Ht.block<3, 3>(6, 3) = Ht.block<3, 3>(3, 6).transpose();
    Matrix9d Hc = Matrix9d::Zero();
    Hc.block<6, 6>(3, 3) = Hc6;
    // Differentiating c g = 2 t gt - f gc once more:
    // c H = 2 gt gt^T + 2 t Ht - g gc^T - gc g^T - f Hc.
    *hessian = (2.0 * gt * gt.transpose() + 2.0 * t * Ht - g * gc.transpose() - gc * g.transpose() -
                f * Hc) /
               c;
  }
  return f;
}

}  // namespace gr
