#pragma once

#include <vector>

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCore>

namespace gr {

/// Sparse Cholesky (CHOLMOD supernodal LLT) that owns its factorization. Its dense kernels
/// run on the BLAS the build links (GR_PORTABLE_BLAS, on by default: ATLAS's generic build),
/// so the factor of a given matrix is the same to the bit on every x86-64 CPU. The symbolic
/// analysis is kept while the sparsity pattern of the matrices it is given stays within the
/// analysed pattern: a matrix whose pattern is a subset is padded with explicit zeros.
/// When a matrix brings new entries the analysis is redone on the union of the two
/// patterns (contact pairs come and go between Newton steps; the union lets the next
/// steps reuse it), or on the new pattern alone once the union has grown past
/// 1.25 times the matrix's own size.
/// With a pattern slack s > 0, a matrix with at most s·nnz off-diagonal entries outside the
/// analysed pattern keeps the analysis: each such entry a_ij is dropped and |a_ij| added to
/// a_jj (its mirror adds to a_ii). That adds [[|a|, -a], [-a, |a|]] per pair, which is PSD,
/// so the factored matrix stays symmetric, is at least A, and is positive definite when A
/// is. Contact pairs appear a few at a time; re-analysing for each costs more than the
/// slightly weaker Newton direction.
class LinearSolver {
 public:
  LinearSolver();
  LinearSolver(const LinearSolver&) = delete;
  LinearSolver& operator=(const LinearSolver&) = delete;

  /// Off-diagonal entries outside the analysed pattern that may be dropped (see above), as
  /// a fraction of the pattern's size; 0 (the default) factors A exactly.
  void set_pattern_slack(double fraction) { pattern_slack_ = fraction; }

  /// Factors A + diag(shift) (with entries outside the pattern compensated, see above). A is
  /// symmetric with both triangles stored (only the lower one is read); the analysed
  /// pattern always holds the whole diagonal.
  /// @param shift per row, added to the diagonal; empty adds nothing.
  /// @return false when CHOLMOD finds the matrix not positive definite numerically.
  bool factorize(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& shift = {});
  /// Solves with the last successful factorization. @pre factorize returned true.
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;

  /// Whether a factorization of an n×n matrix is held (the last factorize succeeded).
  bool has_factor(Eigen::Index n) const { return factored_ && padded_.rows() == n; }
  /// CHOLMOD's count of the floating-point operations one factorization with the current
  /// symbolic analysis takes (0 before any analysis).
  double factorization_flops() const { return factorization_flops_; }

  /// Conjugate gradients on (A + diag(shift)) x = b, preconditioned by the held factor of an
  /// earlier matrix: a matrix that changed little since that factorization is solved with a
  /// few pairs of triangular solves instead of a new factorization. A is symmetric with both
  /// triangles stored; x starts at 0, so each iterate is a descent direction for -b when
  /// the matrix is positive definite. Same arithmetic in the same order on every CPU.
  /// @param tolerance the relative residual |b - (A + diag(shift)) x| / |b| to reach.
  /// @return the iterations taken, or -1 when `max_iterations` did not reach the tolerance
  ///         (x then holds the last iterate).
  /// @pre has_factor(A.rows()).
  int solve_preconditioned(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& shift,
                           const Eigen::VectorXd& b, double tolerance, int max_iterations,
                           Eigen::VectorXd& x) const;

  /// How many symbolic analyses were run (for tests and benchmarks).
  int analysis_count() const { return analysis_count_; }

 private:
  /// Writes A's values into padded_ (the analysed pattern), dropping and compensating at
  /// most `max_dropped` off-diagonal entries outside it; false when more lie outside, or a
  /// diagonal one does.
  bool pad(const Eigen::SparseMatrix<double>& A, Eigen::Index max_dropped);

  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> cholesky_;
  Eigen::SparseMatrix<double> padded_;  ///< the analysed pattern, holding the last values
  std::vector<Eigen::Index> diagonal_;  ///< position of each column's diagonal in padded_, or -1
  std::vector<double> compensation_;    ///< per column, |dropped entries| to add to its diagonal
  double pattern_slack_ = 0.0;
  double factorization_flops_ = 0.0;
  bool factored_ = false;
  int analysis_count_ = 0;
};

}  // namespace gr
