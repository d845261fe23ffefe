#pragma once

#include <Eigen/Eigenvalues>

namespace gr {

/// The nearest positive semi-definite matrix to a symmetric matrix: negative eigenvalues
/// clamped to zero (Teran et al. 2005). Fixed-size stencils keep this allocation-free.
template <typename Matrix>
Matrix project_to_psd(const Matrix& symmetric) {
  Eigen::SelfAdjointEigenSolver<Matrix> eigen(symmetric);
  if (eigen.info() != Eigen::Success) return Matrix::Zero(symmetric.rows(), symmetric.cols());
  if (eigen.eigenvalues().minCoeff() >= 0.0) return symmetric;
  const auto clamped = eigen.eigenvalues().cwiseMax(0.0);
  return eigen.eigenvectors() * clamped.asDiagonal() * eigen.eigenvectors().transpose();
}

}  // namespace gr
