#include "core/energies/anchor_energy.hpp"

#include <cmath>
#include <stdexcept>

#include "core/mesh/boundary_loops.hpp"

namespace gr {

AnchorEnergy::AnchorEnergy(const Eigen::Ref<const MatrixX3d>& rest, std::vector<int> vertices,
                           const DofLayout& layout, std::vector<double> weights, const char* name)
    : vertices_(std::move(vertices)), weights_(std::move(weights)), name_(name),
      rest_(vertices_.size(), 3) {
  if (weights_.empty()) weights_.assign(vertices_.size(), 1.0);
  if (weights_.size() != vertices_.size())
    throw std::invalid_argument("anchor weights: one per anchored vertex");
  for (double w : weights_)
    if (!(w >= 0.0) || !std::isfinite(w))
      throw std::invalid_argument("anchor weights must be finite and non-negative");
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

void AnchorEnergy::set_rest(const Eigen::Ref<const MatrixX3d>& positions) {
  for (std::size_t k = 0; k < vertices_.size(); ++k)
    rest_.row(static_cast<Eigen::Index>(k)) = positions.row(vertices_[k]);
}

double AnchorEnergy::value(const Eigen::Ref<const MatrixX3d>& V, double) const {
  return assembly_.value([&](int e) {
    return 0.5 * weights_[e] * (V.row(vertices_[e]) - rest_.row(e)).squaredNorm();
  });
}

void AnchorEnergy::gradient(const Eigen::Ref<const MatrixX3d>& V, double,
                            Eigen::VectorXd& gradient) const {
  assembly_.gradient(
      [&](int e, LocalVector& g) {
        const Eigen::Vector3d offset = (V.row(vertices_[e]) - rest_.row(e)).transpose();
        g = weights_[e] * offset;
        return 0.5 * g.dot(offset);
      },
      gradient);
}

const Eigen::SparseMatrix<double>& AnchorEnergy::hessian(const Eigen::Ref<const MatrixX3d>&, double,
                                                         bool) const {
  return assembly_.hessian(
      [&](int e, LocalMatrix& h) { h = weights_[e] * LocalMatrix::Identity(); }, false);
}

std::vector<double> vertex_area_shares(const Eigen::Ref<const MatrixX3d>& vertices,
                                       const Eigen::Ref<const MatrixX3i>& faces) {
  std::vector<double> shares(static_cast<std::size_t>(vertices.rows()), 0.0);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Eigen::Vector3d a = vertices.row(faces(f, 0)).transpose();
    const double third = (vertices.row(faces(f, 1)).transpose() - a)
                             .cross(vertices.row(faces(f, 2)).transpose() - a)
                             .norm() /
                         6.0;
    for (int k = 0; k < 3; ++k) shares[static_cast<std::size_t>(faces(f, k))] += third;
  }
  return shares;
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
