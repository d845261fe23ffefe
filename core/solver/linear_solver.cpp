#include "core/solver/linear_solver.hpp"

#include <algorithm>

namespace gr {

LinearSolver::LinearSolver() {
  // A failed factorization is an expected outcome (the caller shifts and retries), not
  // something CHOLMOD should print.
  cholesky_.cholmod().print = 0;
}

bool LinearSolver::same_pattern(const Eigen::SparseMatrix<double>& A) const {
  if (static_cast<std::size_t>(A.cols()) + 1 != outer_.size()) return false;
  if (static_cast<std::size_t>(A.nonZeros()) != inner_.size()) return false;
  return std::equal(outer_.begin(), outer_.end(), A.outerIndexPtr()) &&
         std::equal(inner_.begin(), inner_.end(), A.innerIndexPtr());
}

bool LinearSolver::factorize(const Eigen::SparseMatrix<double>& A, double shift) {
  eigen_assert(A.isCompressed());
  if (!same_pattern(A)) {
    cholesky_.analyzePattern(A);
    outer_.assign(A.outerIndexPtr(), A.outerIndexPtr() + A.cols() + 1);
    inner_.assign(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros());
    ++analysis_count_;
  }
  cholesky_.setShift(shift);
  cholesky_.factorize(A);
  return cholesky_.info() == Eigen::Success;
}

Eigen::VectorXd LinearSolver::solve(const Eigen::VectorXd& b) const { return cholesky_.solve(b); }

}  // namespace gr
