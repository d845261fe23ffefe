#include "core/solver/linear_solver.hpp"

#include <algorithm>
#include <cmath>
#include <mutex>

#include <Eigen/IterativeLinearSolvers>

#include "core/solver/sparse_pattern.hpp"

// Thread controls of the dense kernels under CHOLMOD, looked up at run time: present when
// CHOLMOD is built with OpenMP and the BLAS is OpenBLAS, absent (null) otherwise.
extern "C" {
__attribute__((weak)) void openblas_set_num_threads(int threads);
__attribute__((weak)) void omp_set_max_active_levels(int levels);
}

namespace gr {
namespace {

/// Runs CHOLMOD's supernodal kernels on the calling thread. CHOLMOD asks OpenMP for four
/// threads and OpenBLAS for one per core whatever the machine; both spin while waiting,
/// and on a small machine they compete with the TBB workers that assemble the next
/// Hessian. For the garment problems (about 10k unknowns) one thread per factorization is
/// faster overall, and the factor no longer depends on the thread count.
void use_single_threaded_dense_kernels() {
  static std::once_flag once;
  std::call_once(once, [] {
    if (openblas_set_num_threads) openblas_set_num_threads(1);
    if (omp_set_max_active_levels) omp_set_max_active_levels(0);
  });
}

}  // namespace

LinearSolver::LinearSolver() {
  use_single_threaded_dense_kernels();
  // A failed factorization is an expected outcome (the caller shifts and retries), not
  // something CHOLMOD should print.
  cholesky_.cholmod().print = 0;
}

bool LinearSolver::pad(const Eigen::SparseMatrix<double>& A, Eigen::Index max_dropped) {
  if (padded_.rows() != A.rows() || padded_.cols() != A.cols()) return false;
  double* values = padded_.valuePtr();
  std::fill(values, values + padded_.nonZeros(), 0.0);
  std::fill(compensation_.begin(), compensation_.end(), 0.0);
  Eigen::Index dropped = 0;
  const bool padded = for_each_entry_in_pattern(
      A, padded_, [&](int k, double value) { values[k] = value; },
      [&](Eigen::Index row, Eigen::Index column, double value) {
        const auto c = static_cast<std::size_t>(column);
        if (row == column || diagonal_[c] < 0 || ++dropped > max_dropped) return false;
        compensation_[c] += std::abs(value);
        return true;
      });
  if (!padded) return false;
  if (dropped > 0)
    for (std::size_t c = 0; c < compensation_.size(); ++c)
      if (compensation_[c] != 0.0) values[diagonal_[c]] += compensation_[c];
  return true;
}

bool LinearSolver::factorize(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& shift) {
  const auto max_dropped = static_cast<Eigen::Index>(pattern_slack_ * padded_.nonZeros());
  if (!pad(A, max_dropped)) {
    constexpr double kMaxUnionGrowth = 1.25;
    Eigen::SparseMatrix<double> diagonal(A.rows(), A.cols());
    diagonal.setIdentity();
    Eigen::SparseMatrix<double> pattern = A + 0.0 * diagonal;
    if (padded_.rows() == A.rows() && padded_.cols() == A.cols()) {
      // Union of the two patterns (0 · padded_ keeps its structure, not its values).
      Eigen::SparseMatrix<double> merged = pattern + 0.0 * padded_;
      if (merged.nonZeros() <= kMaxUnionGrowth * A.nonZeros()) pattern = std::move(merged);
    }
    pattern.makeCompressed();
    padded_ = std::move(pattern);
    cholesky_.analyzePattern(padded_);
    ++analysis_count_;
    factorization_flops_ = cholesky_.cholmod().fl;
    diagonal_.assign(static_cast<std::size_t>(padded_.cols()), -1);
    compensation_.assign(static_cast<std::size_t>(padded_.cols()), 0.0);
    for (Eigen::Index c = 0; c < padded_.cols(); ++c)
      for (Eigen::Index k = padded_.outerIndexPtr()[c]; k < padded_.outerIndexPtr()[c + 1]; ++k)
        if (padded_.innerIndexPtr()[k] == c) diagonal_[static_cast<std::size_t>(c)] = k;
    const bool padded = pad(A, 0);
    eigen_assert(padded);
    (void)padded;
  }
  if (shift.size() > 0) {
    double* values = padded_.valuePtr();
    for (Eigen::Index c = 0; c < shift.size(); ++c)
      values[diagonal_[static_cast<std::size_t>(c)]] += shift[c];
  }
  cholesky_.factorize(padded_);
  factored_ = cholesky_.info() == Eigen::Success;
  return factored_;
}

Eigen::VectorXd LinearSolver::solve(const Eigen::VectorXd& b) const { return cholesky_.solve(b); }

namespace {

/// Eigen's preconditioner interface over a factorization held elsewhere: applying it is a
/// solve with that factor.
class HeldFactorPreconditioner {
 public:
  using Factor = Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower>;

  void hold(const Factor& factor) { factor_ = &factor; }
  template <typename Matrix>
  HeldFactorPreconditioner& analyzePattern(const Matrix&) {
    return *this;
  }
  template <typename Matrix>
  HeldFactorPreconditioner& factorize(const Matrix&) {
    return *this;
  }
  template <typename Matrix>
  HeldFactorPreconditioner& compute(const Matrix&) {
    return *this;
  }
  template <typename Rhs>
  Eigen::VectorXd solve(const Rhs& b) const {
    return factor_->solve(Eigen::VectorXd(b));
  }
  Eigen::ComputationInfo info() const { return Eigen::Success; }

 private:
  const Factor* factor_ = nullptr;
};

}  // namespace

int LinearSolver::solve_preconditioned(const Eigen::SparseMatrix<double>& A,
                                       const Eigen::VectorXd& shift, const Eigen::VectorXd& b,
                                       double tolerance, int max_iterations,
                                       Eigen::VectorXd& x) const {
  eigen_assert(has_factor(A.rows()));
  Eigen::SparseMatrix<double> shifted = A;
  if (shift.size() > 0) {
    Eigen::SparseMatrix<double> diagonal(A.rows(), A.cols());
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(static_cast<std::size_t>(shift.size()));
    for (Eigen::Index i = 0; i < shift.size(); ++i)
      entries.emplace_back(static_cast<int>(i), static_cast<int>(i), shift[i]);
    diagonal.setFromTriplets(entries.begin(), entries.end());
    shifted += diagonal;
  }
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper,
                           HeldFactorPreconditioner>
      cg;
  cg.setTolerance(tolerance);
  cg.setMaxIterations(max_iterations);
  cg.compute(shifted);
  cg.preconditioner().hold(cholesky_);
  x = cg.solve(b);
  return cg.info() == Eigen::Success ? static_cast<int>(cg.iterations()) : -1;
}

}  // namespace gr
