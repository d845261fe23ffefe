#include "core/energies/stretch_energy.hpp"

#include <map>
#include <utility>

namespace gr {

StretchEnergy::StretchEnergy(const TriangleMesh& rest, const DofLayout& layout) {
  // A third of each face's rest area goes to each of its edges.
  std::map<std::pair<int, int>, double> edge_area;
  for (int f = 0; f < rest.faces.rows(); ++f) {
    const Vector3d a = rest.vertices.row(rest.faces(f, 0)).transpose();
    const Vector3d b = rest.vertices.row(rest.faces(f, 1)).transpose();
    const Vector3d c = rest.vertices.row(rest.faces(f, 2)).transpose();
    const double area = 0.5 * (b - a).cross(c - a).norm();
    for (int k = 0; k < 3; ++k) {
      int i = rest.faces(f, k), j = rest.faces(f, (k + 1) % 3);
      if (i == j) continue;
      if (i > j) std::swap(i, j);
      edge_area[{i, j}] += area / 3.0;
    }
  }
  for (const auto& [edge, area] : edge_area) {
    const double length = (rest.vertices.row(edge.first) - rest.vertices.row(edge.second)).norm();
    if (!(length > 0.0) || !(area > 0.0)) continue;
    elements_.push_back({{edge.first, edge.second}, length, area / (length * length)});
  }
  build_stencils(layout);
}

StencilDofs<StretchEnergy::kStencilSize> StretchEnergy::element_dofs(const Element& element,
                                                                     const DofLayout& layout) {
  return vertex_dofs<kStencilSize>(element.vertices, layout);
}

StretchEnergy::LocalVector StretchEnergy::gather(const Element& element,
                                                 const Eigen::Ref<const MatrixX3d>& V, double) {
  LocalVector q;
  q << V.row(element.vertices[0]).transpose(), V.row(element.vertices[1]).transpose();
  return q;
}

double StretchEnergy::element_value(const Element& element, const LocalVector& q) {
  const double strain = (q.head<3>() - q.tail<3>()).norm() - element.rest_length;
  return element.weight * strain * strain;
}

double StretchEnergy::element_gradient(const Element& element, const LocalVector& q,
                                       LocalVector& g) {
  const Vector3d d = q.head<3>() - q.tail<3>();
  const double l = d.norm();
  const double strain = l - element.rest_length;
  g.setZero();
  if (l > 0.0) {
    const Vector3d dl = (2.0 * element.weight * strain / l) * d;
    g.head<3>() = dl;
    g.tail<3>() = -dl;
  }
  return element.weight * strain * strain;
}

void StretchEnergy::element_hessian(const Element& element, const LocalVector& q, bool project_psd,
                                    LocalMatrix& h) {
  h.setZero();
  const Vector3d d = q.head<3>() - q.tail<3>();
  const double l = d.norm();
  if (!(l > 0.0)) return;
  const Vector3d u = d / l;
  const Eigen::Matrix3d along = u * u.transpose();
  // Stiffness along the edge 2w, across it 2w (l - L) / l: negative while compressed.
  double across = (l - element.rest_length) / l;
  if (project_psd && across < 0.0) across = 0.0;
  const Eigen::Matrix3d block =
      2.0 * element.weight * (along + across * (Eigen::Matrix3d::Identity() - along));
  h.topLeftCorner<3, 3>() = block;
  h.bottomRightCorner<3, 3>() = block;
  h.topRightCorner<3, 3>() = -block;
  h.bottomLeftCorner<3, 3>() = -block;
}

}  // namespace gr
