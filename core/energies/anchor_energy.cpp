#include "core/energies/anchor_energy.hpp"

#include <cmath>
#include <stdexcept>

#include "core/mesh/boundary_loops.hpp"

namespace gr {

AnchorEnergy::AnchorEnergy(const Eigen::Ref<const MatrixX3d>& rest,
                           const std::vector<int>& vertices, const DofLayout& layout,
                           std::vector<double> weights, const char* name)
    : name_(name) {
  if (weights.empty()) weights.assign(vertices.size(), 1.0);
  if (weights.size() != vertices.size())
    throw std::invalid_argument("anchor weights: one per anchored vertex");
  for (double w : weights)
    if (!(w >= 0.0) || !std::isfinite(w))
      throw std::invalid_argument("anchor weights must be finite and non-negative");
  elements_.reserve(vertices.size());
  for (std::size_t k = 0; k < vertices.size(); ++k) {
    const int v = vertices[k];
    if (v < 0 || v >= rest.rows())
      throw std::invalid_argument("an anchored vertex id is outside the garment");
    elements_.push_back({v, weights[k], rest.row(v).transpose()});
  }
  build_stencils(layout);
}

void AnchorEnergy::set_rest(const Eigen::Ref<const MatrixX3d>& positions) {
  for (Element& element : elements_) element.rest = positions.row(element.vertex).transpose();
}

StencilDofs<AnchorEnergy::kStencilSize> AnchorEnergy::element_dofs(const Element& element,
                                                                   const DofLayout& layout) {
  return vertex_dofs<kStencilSize>(std::array<int, 1>{element.vertex}, layout);
}

AnchorEnergy::LocalVector AnchorEnergy::gather(const Element& element,
                                               const Eigen::Ref<const MatrixX3d>& V, double) {
  return V.row(element.vertex).transpose();
}

double AnchorEnergy::element_value(const Element& element, const LocalVector& q) {
  return 0.5 * element.weight * (q - element.rest).squaredNorm();
}

double AnchorEnergy::element_gradient(const Element& element, const LocalVector& q,
                                      LocalVector& g) {
  const Vector3d offset = q - element.rest;
  g = element.weight * offset;
  return 0.5 * g.dot(offset);
}

void AnchorEnergy::element_hessian(const Element& element, const LocalVector&, bool,
                                   LocalMatrix& h) {
  h = element.weight * LocalMatrix::Identity();
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
