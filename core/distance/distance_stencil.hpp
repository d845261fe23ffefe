#pragma once

#include <array>

#include "core/distance/distance_forms.hpp"

namespace gr {

/// Which smooth form a closest-feature case reduces to.
enum class DistanceForm { PointPoint, PointLine, PointPlane };

/// A closest-feature case on a stencil of vertices: the form and the difference vectors it
/// takes (a, then u, then v; only as many as the form uses).
struct DistanceStencil {
  DistanceForm form;
  std::array<VertexDifference, 3> diffs;
};

/// Squared distance of a closest-feature case on N stencil vertices, with the gradient
/// (3N) and Hessian (3N×3N) with respect to the stacked vertices when the pointers are
/// non-null. All three are computed in one pass, without heap allocation.
template <int N>
double stencil_distance_sq(const DistanceStencil& stencil, const std::array<Vector3d, N>& x,
                           Eigen::Matrix<double, 3 * N, 1>* gradient = nullptr,
                           Eigen::Matrix<double, 3 * N, 3 * N>* hessian = nullptr) {
  const auto& d = stencil.diffs;
  const auto diff = [&](int k) -> Vector3d { return x[d[k].plus] - x[d[k].minus]; };
  switch (stencil.form) {
    case DistanceForm::PointPoint: {
      Vector3d g;
      Eigen::Matrix3d H;
      const double value =
          point_point_form(diff(0), gradient ? &g : nullptr, hessian ? &H : nullptr);
      const std::array<VertexDifference, 1> used{d[0]};
      if (gradient) *gradient = pull_back_gradient<N, 1>(g, used);
      if (hessian) *hessian = pull_back_hessian<N, 1>(H, used);
      return value;
    }
    case DistanceForm::PointLine: {
      Vector6d g;
      Matrix6d H;
      const double value =
          point_line_form(diff(0), diff(1), gradient ? &g : nullptr, hessian ? &H : nullptr);
      const std::array<VertexDifference, 2> used{d[0], d[1]};
      if (gradient) *gradient = pull_back_gradient<N, 2>(g, used);
      if (hessian) *hessian = pull_back_hessian<N, 2>(H, used);
      return value;
    }
    case DistanceForm::PointPlane:
    default: {
      Vector9d g;
      Matrix9d H;
      const double value = point_plane_form(diff(0), diff(1), diff(2), gradient ? &g : nullptr,
                                            hessian ? &H : nullptr);
      if (gradient) *gradient = pull_back_gradient<N, 3>(g, d);
      if (hessian) *hessian = pull_back_hessian<N, 3>(H, d);
      return value;
    }
  }
}

/// Gradient alone of stencil_distance_sq.
template <int N>
Eigen::Matrix<double, 3 * N, 1> stencil_distance_sq_gradient(const DistanceStencil& stencil,
                                                             const std::array<Vector3d, N>& x) {
  Eigen::Matrix<double, 3 * N, 1> g;
  stencil_distance_sq<N>(stencil, x, &g);
  return g;
}

/// Hessian alone of stencil_distance_sq.
template <int N>
Eigen::Matrix<double, 3 * N, 3 * N> stencil_distance_sq_hessian(const DistanceStencil& stencil,
                                                                const std::array<Vector3d, N>& x) {
  Eigen::Matrix<double, 3 * N, 3 * N> H;
  stencil_distance_sq<N>(stencil, x, nullptr, &H);
  return H;
}

}  // namespace gr
