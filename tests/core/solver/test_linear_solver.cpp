#include <filesystem>
#include <vector>

#include <dlfcn.h>

#include <Eigen/SparseCore>
#include <catch2/catch.hpp>

#include "core/solver/linear_solver.hpp"

namespace fs = std::filesystem;

TEST_CASE("the linear solver factors and solves a positive definite system", "[solver]") {
  // The 1D Laplacian plus the identity: tridiagonal [-1, 3, -1].
  const int n = 50;
  Eigen::SparseMatrix<double> A(n, n);
  for (int i = 0; i < n; ++i) {
    A.insert(i, i) = 3.0;
    if (i > 0) A.insert(i, i - 1) = -1.0;
    if (i + 1 < n) A.insert(i, i + 1) = -1.0;
  }
  A.makeCompressed();
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
  const Eigen::VectorXd b = A * x;
  gr::LinearSolver solver;
  REQUIRE(solver.factorize(A));
  CHECK((solver.solve(b) - x).cwiseAbs().maxCoeff() < 1e-12);
  CHECK(solver.analysis_count() == 1);
}

namespace {

/// Tridiagonal [-1, d_i, -1] with d_i = diagonal + slope i: positive definite for diagonal > 2.
Eigen::SparseMatrix<double> tridiagonal(int n, double diagonal, double slope) {
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < n; ++i) {
    entries.emplace_back(i, i, diagonal + slope * i);
    if (i + 1 < n) {
      entries.emplace_back(i, i + 1, -1.0);
      entries.emplace_back(i + 1, i, -1.0);
    }
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  return A;
}

}  // namespace

TEST_CASE("a held factor preconditions conjugate gradients on a changed matrix",
          "[solver][reuse]") {
  const int n = 200;
  gr::LinearSolver solver;
  CHECK_FALSE(solver.has_factor(n));
  CHECK(solver.factorization_flops() == 0.0);
  REQUIRE(solver.factorize(tridiagonal(n, 3.0, 0.0)));
  CHECK(solver.has_factor(n));
  CHECK_FALSE(solver.has_factor(n + 1));
  CHECK(solver.factorization_flops() > 0.0);

  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
  const Eigen::VectorXd shift = Eigen::VectorXd::Constant(n, 0.25);
  SECTION("a matrix close to the factored one: a few iterations reach the tolerance") {
    const Eigen::SparseMatrix<double> A = tridiagonal(n, 3.0, 0.001);
    Eigen::SparseMatrix<double> shifted = A;
    for (int i = 0; i < n; ++i) shifted.coeffRef(i, i) += shift[i];
    const Eigen::VectorXd b = shifted * x;
    Eigen::VectorXd solution;
    const int iterations = solver.solve_preconditioned(A, shift, b, 1e-10, 50, solution);
    CAPTURE(iterations);
    CHECK(iterations > 0);
    CHECK(iterations < 20);
    CHECK((shifted * solution - b).norm() <= 1e-10 * b.norm());
    CHECK((solution - x).cwiseAbs().maxCoeff() < 1e-8);
    // The same arithmetic gives the same bits.
    Eigen::VectorXd again;
    CHECK(solver.solve_preconditioned(A, shift, b, 1e-10, 50, again) == iterations);
    CHECK(again == solution);
  }
  SECTION("too few iterations for the tolerance: -1, and a descent direction still") {
    const Eigen::SparseMatrix<double> A = tridiagonal(n, 3.0, 1.0);
    const Eigen::VectorXd b = A * x;
    Eigen::VectorXd solution;
    CHECK(solver.solve_preconditioned(A, Eigen::VectorXd(), b, 1e-12, 2, solution) == -1);
    REQUIRE(solution.size() == n);
    CHECK(solution.dot(b) > 0.0);
  }
}

#ifdef GR_PORTABLE_BLAS_DIR
TEST_CASE("CHOLMOD's dense kernels come from the CPU-independent BLAS the build names",
          "[solver][determinism]") {
  // What the dynamic linker bound for this test program, as it would for CHOLMOD's calls.
  const fs::path expected = fs::canonical(GR_PORTABLE_BLAS_DIR);
  for (const char* symbol : {"dgemm_", "dsyrk_", "dtrsm_", "dgemv_", "dtrsv_", "dpotrf_"}) {
    CAPTURE(symbol);
    void* address = dlsym(RTLD_DEFAULT, symbol);
    REQUIRE(address != nullptr);
    Dl_info info;
    REQUIRE(dladdr(address, &info) != 0);
    CAPTURE(info.dli_fname);
    CHECK(fs::canonical(info.dli_fname).parent_path() == expected);
  }
  // OpenBLAS, whose kernels depend on the CPU, is not loaded at all.
  CHECK(dlsym(RTLD_DEFAULT, "openblas_get_config") == nullptr);
}
#endif
