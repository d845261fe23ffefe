#include "core/solver/linear_solver.hpp"

#include <algorithm>

namespace gr {

LinearSolver::LinearSolver() {
  // A failed factorization is an expected outcome (the caller shifts and retries), not
  // something CHOLMOD should print.
  cholesky_.cholmod().print = 0;
}

bool LinearSolver::pad(const Eigen::SparseMatrix<double>& A) {
  if (padded_.rows() != A.rows() || padded_.cols() != A.cols()) return false;
  const int* outer = padded_.outerIndexPtr();
  const int* inner = padded_.innerIndexPtr();
  double* values = padded_.valuePtr();
  std::fill(values, values + padded_.nonZeros(), 0.0);
  for (Eigen::Index c = 0; c < A.cols(); ++c) {
    int k = outer[c];
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, c); it; ++it) {
      while (k < outer[c + 1] && inner[k] < it.index()) ++k;
      if (k == outer[c + 1] || inner[k] != it.index()) return false;
      values[k] = it.value();
    }
  }
  return true;
}

bool LinearSolver::factorize(const Eigen::SparseMatrix<double>& A, double shift) {
  if (!pad(A)) {
    constexpr double kMaxUnionGrowth = 1.25;
    Eigen::SparseMatrix<double> pattern = A;
    if (padded_.rows() == A.rows() && padded_.cols() == A.cols()) {
      // Union of the two patterns (0 · padded_ keeps its structure, not its values).
      Eigen::SparseMatrix<double> merged = A + 0.0 * padded_;
      if (merged.nonZeros() <= kMaxUnionGrowth * A.nonZeros()) pattern = std::move(merged);
    }
    pattern.makeCompressed();
    padded_ = std::move(pattern);
    cholesky_.analyzePattern(padded_);
    ++analysis_count_;
    const bool padded = pad(A);
    eigen_assert(padded);
    (void)padded;
  }
  cholesky_.setShift(shift);
  cholesky_.factorize(padded_);
  return cholesky_.info() == Eigen::Success;
}

Eigen::VectorXd LinearSolver::solve(const Eigen::VectorXd& b) const { return cholesky_.solve(b); }

}  // namespace gr
