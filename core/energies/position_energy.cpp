#include "core/energies/position_energy.hpp"

namespace gr {

PositionEnergy::PositionEnergy(const Eigen::Ref<const MatrixX3d>& initial,
                               const std::vector<LoopBone>& loops, const DofLayout& layout) {
  for (const auto& loop : loops) {
    if (!((loop.bone.source_b - loop.bone.source_a).squaredNorm() > 0.0)) continue;
    for (int v : loop.vertices) {
      LocalVector q;
      q << initial.row(v).transpose(), 0.0;
      elements_.push_back({v, loop.bone, bone_parameter(loop.bone, q, nullptr, nullptr)});
    }
  }
  build_stencils(layout);
}

StencilDofs<PositionEnergy::kStencilSize> PositionEnergy::element_dofs(const Element& element,
                                                                       const DofLayout& layout) {
  StencilDofs<kStencilSize> dofs =
      vertex_dofs<kStencilSize>(std::array<int, 1>{element.vertex}, layout);
  dofs[3] = layout.t_index();
  return dofs;
}

PositionEnergy::LocalVector PositionEnergy::gather(const Element& element,
                                                   const Eigen::Ref<const MatrixX3d>& V, double t) {
  LocalVector q;
  q << V.row(element.vertex).transpose(), t;
  return q;
}

double PositionEnergy::bone_parameter(const MovingBone& bone, const LocalVector& q,
                                      LocalVector* gradient, LocalMatrix* hessian) {
  const double t = q[3];
  const Vector3d x = q.head<3>();
  const Vector3d a_rate = bone.target_a - bone.source_a;           // da/dt
  const Vector3d d_rate = bone.target_b - bone.source_b - a_rate;  // d(b - a)/dt
  const Vector3d d = bone.b(t) - bone.a(t);
  const Vector3d r = x - bone.a(t);
  // s = N / D with N = r·d, D = d·d; both are polynomials in t, N linear in x.
  const double N = r.dot(d), D = d.dot(d);
  const double s = N / D;
  if (!gradient && !hessian) return s;
  const double N_t = -a_rate.dot(d) + r.dot(d_rate);
  const double N_tt = -2.0 * a_rate.dot(d_rate);
  const double D_t = 2.0 * d.dot(d_rate);
  const double D_tt = 2.0 * d_rate.dot(d_rate);
  const double s_t = N_t / D - N * D_t / (D * D);
  if (gradient) *gradient << d / D, s_t;
  if (hessian) {
    hessian->setZero();
    const Vector3d s_xt = d_rate / D - d * D_t / (D * D);
    hessian->block<3, 1>(0, 3) = s_xt;
    hessian->block<1, 3>(3, 0) = s_xt.transpose();
    (*hessian)(3, 3) = N_tt / D - 2.0 * N_t * D_t / (D * D) - N * D_tt / (D * D) +
                       2.0 * N * D_t * D_t / (D * D * D);
  }
  return s;
}

double PositionEnergy::element_value(const Element& element, const LocalVector& q) {
  const double residual =
      bone_parameter(element.bone, q, nullptr, nullptr) - element.rest_parameter;
  return 0.5 * residual * residual;
}

double PositionEnergy::element_gradient(const Element& element, const LocalVector& q,
                                        LocalVector& g) {
  LocalVector ds;
  const double residual = bone_parameter(element.bone, q, &ds, nullptr) - element.rest_parameter;
  g = residual * ds;
  return 0.5 * residual * residual;
}

void PositionEnergy::element_hessian(const Element& element, const LocalVector& q, bool,
                                     LocalMatrix& h) {
  LocalVector ds;
  LocalMatrix dds;
  const double residual = bone_parameter(element.bone, q, &ds, &dds) - element.rest_parameter;
  h = ds * ds.transpose() + residual * dds;
}

}  // namespace gr
