#include "core/energies/surface_shape_energy.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace gr {
namespace {

using LocalVector = SurfaceShapeEnergy::LocalVector;
using LocalMatrix = SurfaceShapeEnergy::LocalMatrix;
using ReducedJacobian = Eigen::Matrix<double, 3, 9>;
using ReducedMatrix = Eigen::Matrix<double, 9, 9>;
using Reduction = Eigen::Matrix<double, 9, 12>;

/// Below this ratio (Frobenius norms) of the Hessian's second-order part to its
/// Gauss–Newton part, the PSD Hessian drops the second-order part (see element_hessian).
constexpr double kGaussNewtonRatio = 1e-3;

/// [v]×, so that cross_matrix(v) * u = v × u.
Eigen::Matrix3d cross_matrix(const Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

/// T: local coordinates (x0, x1, x2, x3) → edge vectors (e, u1, u2) = (x1 - x0, x2 - x0,
/// x3 - x0). The energy depends on q only through Tq (it is translation invariant).
const Reduction& reduction() {
  static const Reduction T = [] {
    Reduction m = Reduction::Zero();
    for (int k = 0; k < 3; ++k) {
      m.block<3, 3>(3 * k, 0) = -Eigen::Matrix3d::Identity();
      m.block<3, 3>(3 * k, 3 * (k + 1)) = Eigen::Matrix3d::Identity();
    }
    return m;
  }();
  return T;
}

/// Tᵀ M T for the reduction T below, by blocks: vertex 0's rows and columns are minus the
/// sums of the others'.
LocalMatrix expand_reduced(const ReducedMatrix& M) {
  LocalMatrix h;
  h.bottomRightCorner<9, 9>() = M;
  Eigen::Matrix3d total = Eigen::Matrix3d::Zero();
  for (int j = 0; j < 3; ++j) {
    Eigen::Matrix3d column_sum = Eigen::Matrix3d::Zero();
    for (int i = 0; i < 3; ++i) column_sum += M.block<3, 3>(3 * i, 3 * j);
    h.block<3, 3>(0, 3 + 3 * j) = -column_sum;
    h.block<3, 3>(3 + 3 * j, 0) = -column_sum.transpose();
    total += column_sum;
  }
  h.topLeftCorner<3, 3>() = total;
  return h;
}

/// r = r1 - r2 and, when asked, its 3×9 Jacobian with respect to (e, u1, u2).
Vector3d reconstruction_difference(const SurfaceShapeEnergy::Element& el, const LocalVector& q,
                                   ReducedJacobian* jacobian) {
  const Vector3d x0 = q.segment<3>(0);
  const Vector3d e = q.segment<3>(3) - x0, u1 = q.segment<3>(6) - x0, u2 = q.segment<3>(9) - x0;
  const Vector3d& c1 = el.coefficients_first;
  const Vector3d& c2 = el.coefficients_second;
  const Vector3d r =
      (c1[0] - c2[0]) * e + c1[1] * u1 - c2[1] * u2 + c1[2] * e.cross(u1) - c2[2] * e.cross(u2);
  if (jacobian) {
    const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
    // d(e × u) = -[u]× de + [e]× du.
    jacobian->block<3, 3>(0, 0) =
        (c1[0] - c2[0]) * I - c1[2] * cross_matrix(u1) + c2[2] * cross_matrix(u2);
    jacobian->block<3, 3>(0, 3) = c1[1] * I + c1[2] * cross_matrix(e);
    jacobian->block<3, 3>(0, 6) = -c2[1] * I - c2[2] * cross_matrix(e);
  }
  return r;
}

}  // namespace

SurfaceShapeEnergy::SurfaceShapeEnergy(const TriangleMesh& rest, const DofLayout& layout) {
  // (smaller vertex, larger vertex, face, corner opposite the edge) for every face edge.
  std::vector<std::tuple<int, int, int, int>> half_edges;
  half_edges.reserve(static_cast<std::size_t>(rest.faces.rows()) * 3);
  for (int f = 0; f < rest.faces.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int a = rest.faces(f, (c + 1) % 3);
      const int b = rest.faces(f, (c + 2) % 3);
      half_edges.emplace_back(std::min(a, b), std::max(a, b), f, c);
    }
  std::sort(half_edges.begin(), half_edges.end());

  const auto rest_point = [&](int v) -> Vector3d { return rest.vertices.row(v).transpose(); };
  for (std::size_t i = 0; i < half_edges.size();) {
    std::size_t j = i;
    while (j < half_edges.size() && std::get<0>(half_edges[j]) == std::get<0>(half_edges[i]) &&
           std::get<1>(half_edges[j]) == std::get<1>(half_edges[i]))
      ++j;
    if (j - i == 2) {
      const auto& [a, b, f1, c1] = half_edges[i];
      const int f2 = std::get<2>(half_edges[i + 1]);
      const int c2 = std::get<3>(half_edges[i + 1]);
      Element el;
      el.vertices = {a, b, rest.faces(f1, c1), rest.faces(f2, c2)};
      const Vector3d x0 = rest_point(el.vertices[0]);
      const Vector3d e = rest_point(el.vertices[1]) - x0;
      const Vector3d u1 = rest_point(el.vertices[2]) - x0;
      const Vector3d u2 = rest_point(el.vertices[3]) - x0;
      const Vector3d n1 = e.cross(u1);
      const Vector3d n2 = e.cross(u2);
      const Vector3d w = u2 - u1;
      // A frame whose normal is tiny against its edges cannot be inverted reliably.
      constexpr double kMinimumSine = 1e-8;
      const double scale = e.squaredNorm() + u1.squaredNorm() + u2.squaredNorm();
      if (n1.norm() > kMinimumSine * scale && n2.norm() > kMinimumSine * scale) {
        Eigen::Matrix3d frame1, frame2;
        frame1 << e, u1, n1;
        frame2 << e, u2, n2;
        el.coefficients_first = frame1.partialPivLu().solve(w);
        el.coefficients_second = frame2.partialPivLu().solve(w);
        el.weight = (n1.norm() + n2.norm()) / 6.0;
        elements_.push_back(el);
      }
    }
    i = j;
  }
  build_stencils(layout);
}

StencilDofs<SurfaceShapeEnergy::kStencilSize> SurfaceShapeEnergy::element_dofs(
    const Element& element, const DofLayout& layout) {
  return vertex_dofs<kStencilSize>(element.vertices, layout);
}

LocalVector SurfaceShapeEnergy::gather(const Element& element, const Eigen::Ref<const MatrixX3d>& V,
                                       double) {
  LocalVector q;
  for (int v = 0; v < 4; ++v) q.segment<3>(3 * v) = V.row(element.vertices[v]).transpose();
  return q;
}

double SurfaceShapeEnergy::element_value(const Element& element, const LocalVector& q) {
  return element.weight * reconstruction_difference(element, q, nullptr).squaredNorm();
}

double SurfaceShapeEnergy::element_gradient(const Element& element, const LocalVector& q,
                                            LocalVector& g) {
  ReducedJacobian J;
  const Vector3d r = reconstruction_difference(element, q, &J);
  g = reduction().transpose() * (2.0 * element.weight * J.transpose() * r);
  return element.weight * r.squaredNorm();
}

void SurfaceShapeEnergy::element_hessian(const Element& element, const LocalVector& q,
                                         bool project_psd, LocalMatrix& h) {
  ReducedJacobian J;
  const Vector3d r = reconstruction_difference(element, q, &J);
  ReducedMatrix reduced = J.transpose() * J;
  // Second-order part: r·(e × u) = eᵀ B u with B = -[r]×, for (e, u1) and (e, u2).
  ReducedMatrix second = ReducedMatrix::Zero();
  const Eigen::Matrix3d B = -cross_matrix(r);
  const double c1 = element.coefficients_first[2], c2 = element.coefficients_second[2];
  second.block<3, 3>(0, 3) = c1 * B;
  second.block<3, 3>(3, 0) = c1 * B.transpose();
  second.block<3, 3>(0, 6) = -c2 * B;
  second.block<3, 3>(6, 0) = -c2 * B.transpose();
  if (!project_psd) {
    reduced += second;
  } else if (second.squaredNorm() > kGaussNewtonRatio * kGaussNewtonRatio * reduced.squaredNorm()) {
    // `second` is [[0, M], [Mᵀ, 0]] with M = [c1 B, -c2 B]: its eigenvalues are ±γρ (each
    // twice, γ = |(c1, c2)|, ρ = |r|) and zeros, and its positive part has the closed form
    // ½ [[(MMᵀ)^½, M], [Mᵀ, (MᵀM)^½]] with (MMᵀ)^½ = γρP, (MᵀM)^½ = (ccᵀ/γ) ⊗ ρP,
    // P = I - r̂r̂ᵀ, c = (c1, -c2). JᵀJ plus that part is PSD without an eigen-decomposition
    // and lies above the exact Hessian by the rank-two negative part.
    const double rho = r.norm();
    const double gamma = std::hypot(c1, c2);
    const Eigen::Matrix3d P = rho * (Eigen::Matrix3d::Identity() - r * r.transpose() / (rho * rho));
    reduced += 0.5 * second;
    reduced.block<3, 3>(0, 0) += 0.5 * gamma * P;
    const double c[2] = {c1, -c2};
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j)
        reduced.block<3, 3>(3 + 3 * i, 3 + 3 * j) += 0.5 * c[i] * c[j] / gamma * P;
  }
  // Otherwise the second-order part is negligible against JᵀJ and is dropped (Gauss–Newton):
  // most elements, since the residual r is small wherever the shape is kept.
  reduced *= 2.0 * element.weight;
  h = expand_reduced(reduced);
}

}  // namespace gr
