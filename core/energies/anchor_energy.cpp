#include "core/energies/anchor_energy.hpp"

#include <stdexcept>

#include "core/mesh/boundary_loops.hpp"

namespace gr {

AnchorEnergy::AnchorEnergy(const Eigen::Ref<const MatrixX3d>& rest, std::vector<int> vertices,
                           const DofLayout& layout)
    : vertices_(std::move(vertices)), rest_(vertices_.size(), 3) {
  std::vector<StencilDofs<kStencilSize>> dofs;
  for (std::size_t k = 0; k < vertices_.size(); ++k) {
    const int v = vertices_[k];
    if (v < 0 || v >= rest.rows())
      throw std::invalid_argument("an anchored vertex id is outside the garment");
    rest_.row(static_cast<Eigen::Index>(k)) = rest.row(v);
    dofs.push_back({layout.vertex_dof(v, 0), layout.vertex_dof(v, 1), layout.vertex_dof(v, 2)});
  }
  assembly_ = StencilAssembly<kStencilSize>(std::move(dofs), layout.dof_count());
}

double AnchorEnergy::value(const Eigen::Ref<const MatrixX3d>& V, double) const {
  return assembly_.value(
      [&](int e) { return 0.5 * (V.row(vertices_[e]) - rest_.row(e)).squaredNorm(); });
}

void AnchorEnergy::gradient(const Eigen::Ref<const MatrixX3d>& V, double,
                            Eigen::VectorXd& gradient) const {
  assembly_.gradient(
      [&](int e, LocalVector& g) {
        g = (V.row(vertices_[e]) - rest_.row(e)).transpose();
        return 0.5 * g.squaredNorm();
      },
      gradient);
}

const Eigen::SparseMatrix<double>& AnchorEnergy::hessian(const Eigen::Ref<const MatrixX3d>&, double,
                                                         bool) const {
  return assembly_.hessian([](int, LocalMatrix& h) { h.setIdentity(); }, false);
}

std::vector<int> boundary_loop_vertices(const Eigen::Ref<const MatrixX3i>& faces) {
  std::vector<int> vertices;
  std::vector<bool> seen;
  for (const auto& loop : boundary_loops(faces))
    for (int v : loop) {
      if (v >= static_cast<int>(seen.size())) seen.resize(static_cast<std::size_t>(v) + 1, false);
      if (seen[static_cast<std::size_t>(v)]) continue;
      seen[static_cast<std::size_t>(v)] = true;
      vertices.push_back(v);
    }
  return vertices;
}

}  // namespace gr
