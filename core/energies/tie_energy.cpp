#include "core/energies/tie_energy.hpp"

#include <stdexcept>

namespace gr {

TieEnergy::TieEnergy(std::vector<Element> pairs, const DofLayout& layout)
    : pairs_(std::move(pairs)) {
  for (const auto& [a, b] : pairs_) {
    if (a < 0 || b < 0 || a >= layout.garment_vertex_count || b >= layout.garment_vertex_count)
      throw std::invalid_argument("a tied vertex id is outside the garment");
    if (a == b) throw std::invalid_argument("a vertex cannot be tied to itself");
  }
  build_stencils(layout);
}

StencilDofs<TieEnergy::kStencilSize> TieEnergy::element_dofs(const Element& pair,
                                                             const DofLayout& layout) {
  return vertex_dofs<kStencilSize>(pair, layout);
}

TieEnergy::LocalVector TieEnergy::gather(const Element& pair, const Eigen::Ref<const MatrixX3d>& V,
                                         double) {
  LocalVector q;
  q << V.row(pair[0]).transpose(), V.row(pair[1]).transpose();
  return q;
}

double TieEnergy::element_value(const Element&, const LocalVector& q) {
  return 0.5 * (q.head<3>() - q.tail<3>()).squaredNorm();
}

double TieEnergy::element_gradient(const Element&, const LocalVector& q, LocalVector& g) {
  const Vector3d d = q.head<3>() - q.tail<3>();
  g << d, -d;
  return 0.5 * d.squaredNorm();
}

void TieEnergy::element_hessian(const Element&, const LocalVector&, bool, LocalMatrix& h) {
  h.setZero();
  h.topLeftCorner<3, 3>().setIdentity();
  h.bottomRightCorner<3, 3>().setIdentity();
  h.topRightCorner<3, 3>() = -Eigen::Matrix3d::Identity();
  h.bottomLeftCorner<3, 3>() = -Eigen::Matrix3d::Identity();
}

}  // namespace gr
