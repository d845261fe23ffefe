#pragma once

#include <vector>

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCore>

namespace gr {

/// Sparse Cholesky (CHOLMOD supernodal LLT) that owns its factorization. The symbolic
/// analysis is kept while the sparsity pattern of the matrices it is given stays within the
/// analysed pattern: a matrix whose pattern is a subset is padded with explicit zeros.
/// When a matrix brings new entries the analysis is redone on the union of the two
/// patterns (contact pairs come and go between Newton steps; the union lets the next
/// steps reuse it), or on the new pattern alone once the union has grown past
/// 1.25 times the matrix's own size.
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
  /// Writes A's values into padded_ (the analysed pattern); false when A has an entry
  /// outside it.
  bool pad(const Eigen::SparseMatrix<double>& A);

  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> cholesky_;
  Eigen::SparseMatrix<double> padded_;  ///< the analysed pattern, holding the last values
  int analysis_count_ = 0;
};

}  // namespace gr
