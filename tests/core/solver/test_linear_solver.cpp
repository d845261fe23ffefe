#include <filesystem>

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
