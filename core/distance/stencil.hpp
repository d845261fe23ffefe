#pragma once

#include <array>

#include <Eigen/Core>

namespace gr {

/// Fixed-size local stencils: 2, 3 or 4 vertices, 3 coordinates each, vertex-major.
using Vector6d = Eigen::Matrix<double, 6, 1>;
using Vector9d = Eigen::Matrix<double, 9, 1>;
using Vector12d = Eigen::Matrix<double, 12, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Matrix9d = Eigen::Matrix<double, 9, 9>;
using Matrix12d = Eigen::Matrix<double, 12, 12>;

/// One difference vector x[plus] - x[minus] between two stencil vertices.
struct VertexDifference {
  int plus;
  int minus;
};

/// Gradient with respect to the stencil's vertices of a function of K difference vectors,
/// given its gradient `g` (3K) with respect to the differences: the chain rule through the
/// constant ±1 map, written out so no dense 3K×3N matrix is formed.
template <int N, int K>
Eigen::Matrix<double, 3 * N, 1> pull_back_gradient(const Eigen::Matrix<double, 3 * K, 1>& g,
                                                   const std::array<VertexDifference, K>& diffs) {
  Eigen::Matrix<double, 3 * N, 1> out = Eigen::Matrix<double, 3 * N, 1>::Zero();
  for (int k = 0; k < K; ++k) {
    out.template segment<3>(3 * diffs[k].plus) += g.template segment<3>(3 * k);
    out.template segment<3>(3 * diffs[k].minus) -= g.template segment<3>(3 * k);
  }
  return out;
}

/// Hessian with respect to the stencil's vertices of a function of K difference vectors,
/// given its Hessian `H` (3K×3K) with respect to the differences (S^T H S for the ±1 map S).
template <int N, int K>
Eigen::Matrix<double, 3 * N, 3 * N> pull_back_hessian(
    const Eigen::Matrix<double, 3 * K, 3 * K>& H, const std::array<VertexDifference, K>& diffs) {
  Eigen::Matrix<double, 3 * N, 3 * N> out = Eigen::Matrix<double, 3 * N, 3 * N>::Zero();
  for (int k = 0; k < K; ++k) {
    for (int l = 0; l < K; ++l) {
      const Eigen::Matrix3d block = H.template block<3, 3>(3 * k, 3 * l);
      const int kp = 3 * diffs[k].plus, km = 3 * diffs[k].minus;
      const int lp = 3 * diffs[l].plus, lm = 3 * diffs[l].minus;
      out.template block<3, 3>(kp, lp) += block;
      out.template block<3, 3>(kp, lm) -= block;
      out.template block<3, 3>(km, lp) -= block;
      out.template block<3, 3>(km, lm) += block;
    }
  }
  return out;
}

}  // namespace gr
