#pragma once

#include <vector>

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCore>

namespace gr {

/// Sparse Cholesky (CHOLMOD supernodal LLT) that owns its factorization. The symbolic
/// analysis is kept while the sparsity pattern of the matrices it is given stays the same,
/// and redone when the pattern changes.
class LinearSolver {
 public:
  LinearSolver();
  LinearSolver(const LinearSolver&) = delete;
  LinearSolver& operator=(const LinearSolver&) = delete;

  /// Factors A + shift·I. A is symmetric with both triangles stored (only the lower one is
  /// read). @return false when CHOLMOD finds A + shift·I not positive definite numerically.
  bool factorize(const Eigen::SparseMatrix<double>& A, double shift = 0.0);
  /// Solves with the last successful factorization. @pre factorize returned true.
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;

  /// How many symbolic analyses were run (for tests and benchmarks).
  int analysis_count() const { return analysis_count_; }

 private:
  bool same_pattern(const Eigen::SparseMatrix<double>& A) const;

  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> cholesky_;
  std::vector<int> outer_, inner_;
  int analysis_count_ = 0;
};

}  // namespace gr
