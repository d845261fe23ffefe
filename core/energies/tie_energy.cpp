#include "core/energies/tie_energy.hpp"

#include <stdexcept>

namespace gr {

TieEnergy::TieEnergy(std::vector<std::array<int, 2>> pairs, const DofLayout& layout)
    : pairs_(std::move(pairs)) {
  std::vector<StencilDofs<kStencilSize>> dofs;
  for (const auto& [a, b] : pairs_) {
    if (a < 0 || b < 0 || a >= layout.garment_vertex_count || b >= layout.garment_vertex_count)
      throw std::invalid_argument("a tied vertex id is outside the garment");
    if (a == b) throw std::invalid_argument("a vertex cannot be tied to itself");
    dofs.push_back({layout.vertex_dof(a, 0), layout.vertex_dof(a, 1), layout.vertex_dof(a, 2),
                    layout.vertex_dof(b, 0), layout.vertex_dof(b, 1), layout.vertex_dof(b, 2)});
  }
  assembly_ = StencilAssembly<kStencilSize>(std::move(dofs), layout.dof_count());
}

double TieEnergy::value(const Eigen::Ref<const MatrixX3d>& V, double) const {
  return assembly_.value([&](int e) {
    const auto& [a, b] = pairs_[static_cast<std::size_t>(e)];
    return 0.5 * (V.row(a) - V.row(b)).squaredNorm();
  });
}

void TieEnergy::gradient(const Eigen::Ref<const MatrixX3d>& V, double,
                         Eigen::VectorXd& gradient) const {
  assembly_.gradient(
      [&](int e, LocalVector& g) {
        const auto& [a, b] = pairs_[static_cast<std::size_t>(e)];
        const Eigen::Vector3d d = (V.row(a) - V.row(b)).transpose();
        g << d, -d;
        return 0.5 * d.squaredNorm();
      },
      gradient);
}

const Eigen::SparseMatrix<double>& TieEnergy::hessian(const Eigen::Ref<const MatrixX3d>&, double,
                                                      bool) const {
  return assembly_.hessian(
      [&](int, LocalMatrix& h) {
        h.setZero();
        h.topLeftCorner<3, 3>().setIdentity();
        h.bottomRightCorner<3, 3>().setIdentity();
        h.topRightCorner<3, 3>() = -Eigen::Matrix3d::Identity();
        h.bottomLeftCorner<3, 3>() = -Eigen::Matrix3d::Identity();
      },
      false);
}

}  // namespace gr
