#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "core/common/psd_projection.hpp"
#include "core/solver/projected_newton.hpp"

using namespace gr;

namespace {

/// Keeps every step the solver reports.
class RecordedSteps : public Interrupter {
 public:
  void step(const SolverStep& step) override { steps.push_back(step); }
  std::vector<SolverStep> steps;
};

/// 1/2 xᵀ A x - bᵀ x with A a sparse SPD tridiagonal matrix.
class QuadraticProblem : public Problem {
 public:
  explicit QuadraticProblem(int n) : A_(n, n), b_(Eigen::VectorXd::LinSpaced(n, -1.0, 2.0)) {
    std::vector<Eigen::Triplet<double>> t;
    for (int i = 0; i < n; ++i) {
      t.emplace_back(i, i, 4.0 + i);
      if (i + 1 < n) {
        t.emplace_back(i, i + 1, -1.0);
        t.emplace_back(i + 1, i, -1.0);
      }
    }
    A_.setFromTriplets(t.begin(), t.end());
  }
  int dof_count() const override { return static_cast<int>(A_.rows()); }
  double value(const Eigen::VectorXd& x) override { return 0.5 * x.dot(A_ * x) - b_.dot(x); }
  void gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) override { g = A_ * x - b_; }
  void hessian(const Eigen::VectorXd&, Eigen::SparseMatrix<double>& H) override { H = A_; }
  Eigen::VectorXd solution() const { return Eigen::MatrixXd(A_).ldlt().solve(b_); }

 private:
  Eigen::SparseMatrix<double> A_;
  Eigen::VectorXd b_;
};

/// Sum over pairs of Rosenbrock functions 100 (y - x²)² + (1 - x)², each pair's 2×2 Hessian
/// projected to PSD as an element would be.
class RosenbrockProblem : public Problem {
 public:
  explicit RosenbrockProblem(int pairs) : pairs_(pairs) {}
  int dof_count() const override { return 2 * pairs_; }
  double value(const Eigen::VectorXd& z) override {
    double sum = 0.0;
    for (int i = 0; i < pairs_; ++i) {
      const double x = z[2 * i], y = z[2 * i + 1];
      sum += 100.0 * (y - x * x) * (y - x * x) + (1.0 - x) * (1.0 - x);
    }
    return sum;
  }
  void gradient(const Eigen::VectorXd& z, Eigen::VectorXd& g) override {
    g.resize(z.size());
    for (int i = 0; i < pairs_; ++i) {
      const double x = z[2 * i], y = z[2 * i + 1];
      g[2 * i] = -400.0 * x * (y - x * x) - 2.0 * (1.0 - x);
      g[2 * i + 1] = 200.0 * (y - x * x);
    }
  }
  void hessian(const Eigen::VectorXd& z, Eigen::SparseMatrix<double>& H) override {
    std::vector<Eigen::Triplet<double>> t;
    for (int i = 0; i < pairs_; ++i) {
      const double x = z[2 * i], y = z[2 * i + 1];
      Eigen::Matrix2d h;
      h << 1200.0 * x * x - 400.0 * y + 2.0, -400.0 * x, -400.0 * x, 200.0;
      h = project_to_psd(h);
      for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) t.emplace_back(2 * i + a, 2 * i + b, h(a, b));
    }
    H.resize(z.size(), z.size());
    H.setFromTriplets(t.begin(), t.end());
  }

 private:
  int pairs_;
};

}  // namespace

TEST_CASE("projected Newton: a convex quadratic converges in a few steps", "[solver][newton]") {
  QuadraticProblem problem(50);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(50);
  ProjectedNewton newton;
  newton.options().step_tolerance = 0.0;
  newton.options().gradient_tolerance = 1e-14;
  const NewtonResult result = newton.minimize(problem, x);
  CHECK(result.status == SolverStatus::kConverged);
  // Each damped step leaves a fraction mu (1e-6, falling to 1e-8) of the error.
  CHECK(result.iterations <= 4);
  CHECK((x - problem.solution()).norm() < 1e-12);
  CHECK(result.energy == Approx(problem.value(problem.solution())).epsilon(1e-12));
}

TEST_CASE("projected Newton: Rosenbrock pairs with PSD projection", "[solver][newton]") {
  RosenbrockProblem problem(20);
  Eigen::VectorXd x(40);
  for (int i = 0; i < 20; ++i) x.segment<2>(2 * i) << -1.2 + 0.05 * i, 1.0 - 0.1 * i;
  ProjectedNewton newton;
  RecordedSteps recorded;
  const NewtonResult result = newton.minimize(problem, x, recorded);
  CHECK(result.status == SolverStatus::kConverged);
  CHECK(static_cast<int>(recorded.steps.size()) == result.iterations);
  double last_energy = std::numeric_limits<double>::infinity();
  for (const SolverStep& step : recorded.steps) {
    CHECK(step.energy <= last_energy);
    last_energy = step.energy;
  }
  CHECK((x - Eigen::VectorXd::Ones(40)).lpNorm<Eigen::Infinity>() < 1e-5);
  CHECK(result.iterations < 100);
}

/// The quadratic plus a quartic sum_i x_i⁴ / 4: its Hessian changes a little from one
/// Newton step to the next, as a garment's does between short steps.
class QuarticProblem : public QuadraticProblem {
 public:
  using QuadraticProblem::QuadraticProblem;
  double value(const Eigen::VectorXd& x) override {
    return QuadraticProblem::value(x) + 0.25 * x.array().pow(4).sum();
  }
  void gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) override {
    QuadraticProblem::gradient(x, g);
    g += x.array().cube().matrix();
  }
  void hessian(const Eigen::VectorXd& x, Eigen::SparseMatrix<double>& H) override {
    QuadraticProblem::hessian(x, H);
    for (Eigen::Index i = 0; i < x.size(); ++i) H.coeffRef(i, i) += 3.0 * x[i] * x[i];
  }
};

TEST_CASE("projected Newton: a held factor is reused across steps where it still converges",
          "[solver][newton][reuse]") {
  const int n = 60;
  const Eigen::VectorXd start = Eigen::VectorXd::LinSpaced(n, 3.0, -2.0);
  QuarticProblem problem(n);
  const auto solve = [&](double reuse_factor_flops, Eigen::VectorXd& x) {
    x = start;
    ProjectedNewton newton;
    newton.options().gradient_tolerance = 1e-12;
    newton.options().step_tolerance = 0.0;
    newton.options().reuse_factor_flops = reuse_factor_flops;
    newton.options().reuse_tolerance = 1e-8;
    return newton.minimize(problem, x);
  };
  Eigen::VectorXd exact;
  const NewtonResult factored = solve(0.0, exact);
  REQUIRE(factored.status == SolverStatus::kConverged);
  CHECK(factored.reused_factor_steps == 0);
  CHECK(factored.factorizations >= factored.iterations);

  Eigen::VectorXd reused;
  const NewtonResult result = solve(1.0, reused);  // this small system qualifies
  CAPTURE(factored.iterations, result.iterations, result.factorizations, result.reused_factor_steps,
          result.cg_iterations);
  CHECK(result.status == SolverStatus::kConverged);
  CHECK(result.reused_factor_steps > 0);
  CHECK(result.cg_iterations >= result.reused_factor_steps);
  CHECK(result.factorizations < result.iterations);
  CHECK((reused - exact).lpNorm<Eigen::Infinity>() < 1e-9);

  SECTION("above the factorization's cost: every step factors, the same bits as off") {
    Eigen::VectorXd x;
    const NewtonResult off = solve(1e30, x);
    CHECK(off.reused_factor_steps == 0);
    CHECK(off.iterations == factored.iterations);
    CHECK(x == exact);
  }
}

/// Rosenbrock pairs whose goal is met once every x is within `reach` of the minimizer's 1.
class RosenbrockWithGoal : public RosenbrockProblem {
 public:
  RosenbrockWithGoal(int pairs, double reach) : RosenbrockProblem(pairs), reach_(reach) {}
  bool goal_reached(const Eigen::VectorXd& z) override {
    ++goal_checks;
    for (Eigen::Index i = 0; i < z.size(); i += 2)
      if (std::abs(z[i] - 1.0) > reach_) return false;
    return true;
  }
  int goal_checks = 0;

 private:
  double reach_;
};

TEST_CASE("projected Newton: ends where the problem's goal is met", "[solver][newton]") {
  Eigen::VectorXd start(2);
  start << -1.2, 1.0;
  Eigen::VectorXd x = start;
  RosenbrockProblem plain(1);
  const NewtonResult full = ProjectedNewton().minimize(plain, x);
  REQUIRE(full.status == SolverStatus::kConverged);

  x = start;
  RosenbrockWithGoal problem(1, 0.1);
  const NewtonResult result = ProjectedNewton().minimize(problem, x);
  CHECK(result.status == SolverStatus::kGoalReached);
  CHECK(std::abs(x[0] - 1.0) <= 0.1);
  CHECK(result.iterations < full.iterations);
  // Asked at the start point and after each accepted step, the last time with success.
  CHECK(problem.goal_checks == result.iterations + 1);
  CHECK(result.energy == problem.value(x));

  SECTION("a start point that already meets it takes no step") {
    const Eigen::VectorXd met = x;
    const NewtonResult again = ProjectedNewton().minimize(problem, x);
    CHECK(again.status == SolverStatus::kGoalReached);
    CHECK(again.iterations == 0);
    CHECK(x == met);
  }
}

TEST_CASE("projected Newton: reports the iteration cap", "[solver][newton]") {
  RosenbrockProblem problem(1);
  Eigen::VectorXd x(2);
  x << -1.2, 1.0;
  const Eigen::VectorXd start = x;
  NewtonOptions options;
  options.max_iterations = 2;
  ProjectedNewton newton(options);
  const NewtonResult result = newton.minimize(problem, x);
  CHECK(result.status == SolverStatus::kIterationLimit);
  CHECK(result.iterations == 2);
  CHECK(result.energy < problem.value(start));
  CHECK(result.energy == problem.value(x));
  CHECK_FALSE(result.message.empty());
}

TEST_CASE("projected Newton: non-finite energy and no-descent statuses", "[solver][newton]") {
  SECTION("non-finite start energy") {
    struct NanProblem : QuadraticProblem {
      NanProblem() : QuadraticProblem(3) {}
      double value(const Eigen::VectorXd&) override { return std::nan(""); }
    } problem;
    Eigen::VectorXd x = Eigen::VectorXd::Zero(3);
    CHECK(ProjectedNewton().minimize(problem, x).status == SolverStatus::kNonFiniteEnergy);
  }
  SECTION("non-finite gradient") {
    struct InfGradient : QuadraticProblem {
      InfGradient() : QuadraticProblem(3) {}
      void gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) override {
        QuadraticProblem::gradient(x, g);
        g[1] = std::numeric_limits<double>::infinity();
      }
    } problem;
    Eigen::VectorXd x = Eigen::VectorXd::Zero(3);
    CHECK(ProjectedNewton().minimize(problem, x).status == SolverStatus::kNonFiniteEnergy);
  }
  SECTION("a gradient that points the wrong way") {
    struct WrongGradient : QuadraticProblem {
      WrongGradient() : QuadraticProblem(3) {}
      void gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) override {
        QuadraticProblem::gradient(x, g);
        g = -g;
      }
      void hessian(const Eigen::VectorXd&, Eigen::SparseMatrix<double>& H) override {
        H.resize(3, 3);
        H.setIdentity();
      }
    } problem;
    Eigen::VectorXd x = Eigen::VectorXd::Zero(3);
    const NewtonResult result = ProjectedNewton().minimize(problem, x);
    CHECK(result.status == SolverStatus::kNoDescent);
    CHECK(x.norm() == 0.0);
  }
  SECTION("CCD allows no step") {
    struct Blocked : QuadraticProblem {
      Blocked() : QuadraticProblem(3) {}
      double max_step(const Eigen::VectorXd&, const Eigen::VectorXd&) override { return 0.0; }
    } problem;
    Eigen::VectorXd x = Eigen::VectorXd::Zero(3);
    CHECK(ProjectedNewton().minimize(problem, x).status == SolverStatus::kNoDescent);
  }
}

TEST_CASE("projected Newton: steps stay within the problem's safe bound", "[solver][newton]") {
  struct Bounded : QuadraticProblem {
    Bounded() : QuadraticProblem(4) {}
    double max_step(const Eigen::VectorXd&, const Eigen::VectorXd&) override { return 0.25; }
  } problem;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(4);
  const Eigen::VectorXd solution = problem.solution();
  ProjectedNewton newton;
  RecordedSteps recorded;
  newton.minimize(problem, x, recorded);
  CHECK(recorded.steps.size() > 1);
  for (const SolverStep& step : recorded.steps) CHECK(step.step <= 0.25);
  CHECK((x - solution).lpNorm<Eigen::Infinity>() < 1e-5);
}

TEST_CASE("projected Newton: stops when the energy stagnates over its window", "[solver][newton]") {
  // A tiny safe bound makes every step a small fraction of the Newton step: the energy
  // keeps falling, ever more slowly, and neither the gradient nor the step test is met.
  struct Creeping : QuadraticProblem {
    Creeping() : QuadraticProblem(4) {}
    double max_step(const Eigen::VectorXd&, const Eigen::VectorXd&) override { return 0.01; }
  };
  NewtonOptions options;
  options.max_iterations = 5000;
  options.energy_window = 5;
  SECTION("with the test") {
    Creeping problem;
    Eigen::VectorXd x = Eigen::VectorXd::Zero(4);
    options.energy_tolerance = 1e-3;
    std::vector<double> energies{problem.value(x)};
    RecordedSteps recorded;
    const NewtonResult result = ProjectedNewton(options).minimize(problem, x, recorded);
    for (const SolverStep& step : recorded.steps) energies.push_back(step.energy);
    CHECK(result.status == SolverStatus::kConverged);
    CHECK(result.message.find("energy fell") != std::string::npos);
    REQUIRE(result.iterations >= options.energy_window);
    const double last = energies.back();
    const double before =
        energies[energies.size() - 1 - static_cast<std::size_t>(options.energy_window)];
    CHECK(before - last <= options.energy_tolerance * std::abs(last));
    // One window earlier the decrease was still above the tolerance.
    const double earlier =
        energies[energies.size() - 2 - static_cast<std::size_t>(options.energy_window)];
    const double previous = energies[energies.size() - 2];
    CHECK(earlier - previous > options.energy_tolerance * std::abs(previous));
  }
  SECTION("without it the solve runs on") {
    Creeping problem;
    Eigen::VectorXd x = Eigen::VectorXd::Zero(4);
    options.energy_tolerance = 0.0;
    options.max_iterations = 300;
    CHECK(ProjectedNewton(options).minimize(problem, x).status == SolverStatus::kIterationLimit);
  }
}

TEST_CASE("linear solver: symbolic analysis reused within the analysed pattern - shift on failure",
          "[solver][linear]") {
  QuadraticProblem problem(30);
  Eigen::SparseMatrix<double> A;
  problem.hessian(Eigen::VectorXd(), A);
  A.makeCompressed();
  LinearSolver solver;
  REQUIRE(solver.factorize(A));
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(30);
  CHECK((A * solver.solve(b) - b).norm() < 1e-12);
  Eigen::SparseMatrix<double> scaled = 2.0 * A;
  scaled.makeCompressed();
  REQUIRE(solver.factorize(scaled));
  CHECK(solver.analysis_count() == 1);
  CHECK((scaled * solver.solve(b) - b).norm() < 1e-12);

  const auto coupled = [&A](int i, int j) {
    Eigen::SparseMatrix<double> M = A;
    M.coeffRef(i, j) = M.coeffRef(j, i) = 0.1;
    M.makeCompressed();
    return M;
  };
  const Eigen::SparseMatrix<double> wider = coupled(0, 29);
  REQUIRE(solver.factorize(wider));
  CHECK(solver.analysis_count() == 2);

  Eigen::SparseMatrix<double> indefinite = A;
  indefinite.coeffRef(5, 5) = -1.0;
  indefinite.makeCompressed();
  CHECK_FALSE(solver.factorize(indefinite));
  CHECK(solver.analysis_count() == 2);  // A's pattern is within the analysed one
  REQUIRE(solver.factorize(indefinite, Eigen::VectorXd::Constant(30, 10.0)));
  CHECK(solver.analysis_count() == 2);
  Eigen::SparseMatrix<double> identity(30, 30);
  identity.setIdentity();
  const Eigen::SparseMatrix<double> shifted = indefinite + 10.0 * identity;
  CHECK((shifted * solver.solve(b) - b).norm() < 1e-12);

  SECTION("a matrix with new entries is analysed on the union of the patterns") {
    REQUIRE(solver.factorize(coupled(3, 17)));
    CHECK(solver.analysis_count() == 3);
    REQUIRE(solver.factorize(wider));  // still within the union
    CHECK(solver.analysis_count() == 3);
    CHECK((wider * solver.solve(b) - b).norm() < 1e-12);
  }
}

TEST_CASE(
    "linear solver: with pattern slack a few new entries keep the analysis and are "
    "compensated on the diagonal",
    "[solver][linear]") {
  const int n = 400;
  QuadraticProblem problem(n);
  Eigen::SparseMatrix<double> A;
  problem.hessian(Eigen::VectorXd(), A);
  A.makeCompressed();
  LinearSolver solver;
  solver.set_pattern_slack(0.01);  // the tridiagonal pattern has 1198 entries: 11 may drop
  REQUIRE(solver.factorize(A));
  REQUIRE(solver.analysis_count() == 1);

  const auto with_couplings = [&A](const std::vector<std::pair<int, int>>& pairs, double value) {
    Eigen::SparseMatrix<double> M = A;
    for (const auto& [i, j] : pairs) M.coeffRef(i, j) = M.coeffRef(j, i) = value;
    M.makeCompressed();
    return M;
  };
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, 1.0, 2.0);
  SECTION("within the slack: same analysis, the solve is of A plus [[|a|, -a], [-a, |a|]]") {
    const double a = -0.7;
    const Eigen::SparseMatrix<double> M = with_couplings({{0, 200}, {10, 300}}, a);
    REQUIRE(solver.factorize(M));
    CHECK(solver.analysis_count() == 1);
    Eigen::MatrixXd compensated = Eigen::MatrixXd(A);
    for (const int i : {0, 200, 10, 300}) compensated(i, i) += std::abs(a);
    const Eigen::VectorXd x = solver.solve(b);
    CHECK((compensated * x - b).norm() <= 1e-10 * b.norm());
    // The compensated matrix exceeds M by a PSD matrix.
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> excess(compensated - Eigen::MatrixXd(M));
    CHECK(excess.eigenvalues().minCoeff() >= -1e-12);
  }
  SECTION("beyond the slack: analysed again on the union, solved exactly") {
    std::vector<std::pair<int, int>> pairs;
    for (int k = 0; k < 12; ++k) pairs.emplace_back(k, 100 + 20 * k);
    const Eigen::SparseMatrix<double> M = with_couplings(pairs, -0.5);
    REQUIRE(solver.factorize(M));
    CHECK(solver.analysis_count() == 2);
    CHECK((M * solver.solve(b) - b).norm() <= 1e-10 * b.norm());
  }
}

namespace {

/// A chain of springs 1/2 sum (x_{i+1} - x_i - 1)^2 plus a force f on the first dof: the
/// Hessian is singular (a free translation) and the force has a part along it, so without
/// damping the Newton system has no solution.
class FreeChainProblem : public Problem {
 public:
  FreeChainProblem(int n, double force) : n_(n), force_(force) {}
  int dof_count() const override { return n_; }
  double value(const Eigen::VectorXd& x) override {
    double sum = -force_ * x[0];
    for (int i = 0; i + 1 < n_; ++i) sum += 0.5 * std::pow(x[i + 1] - x[i] - 1.0, 2);
    return sum;
  }
  void gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) override {
    g.setZero(n_);
    g[0] = -force_;
    for (int i = 0; i + 1 < n_; ++i) {
      const double r = x[i + 1] - x[i] - 1.0;
      g[i + 1] += r;
      g[i] -= r;
    }
  }
  void hessian(const Eigen::VectorXd&, Eigen::SparseMatrix<double>& H) override {
    std::vector<Eigen::Triplet<double>> t;
    for (int i = 0; i + 1 < n_; ++i) {
      t.emplace_back(i, i, 1.0);
      t.emplace_back(i + 1, i + 1, 1.0);
      t.emplace_back(i, i + 1, -1.0);
      t.emplace_back(i + 1, i, -1.0);
    }
    H.resize(n_, n_);
    H.setFromTriplets(t.begin(), t.end());
  }

 private:
  int n_;
  double force_;
};

}  // namespace

TEST_CASE("projected Newton: a singular system is damped, never left to rounding",
          "[solver][newton][damping]") {
  SECTION("no force along the null space: converges to the rest shape where it started") {
    FreeChainProblem problem(20, 0.0);
    Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(20, 0.0, 30.0);
    ProjectedNewton newton;
    newton.options().gradient_tolerance = 1e-10;
    const NewtonResult result = newton.minimize(problem, x);
    CAPTURE(result.message);
    CHECK(result.converged());
    CHECK(result.iterations <= 5);
    CHECK(result.gradient_descent_steps == 0);
    // Only the chain's shape changes: its mean stays (the damping adds no pull anywhere).
    CHECK(x.mean() == Approx(15.0).epsilon(1e-9));
    for (int i = 0; i + 1 < 20; ++i) CHECK(x[i + 1] - x[i] == Approx(1.0).epsilon(1e-8));
  }
  SECTION(
      "a force along the null space: every step is finite, bounded by the trust radius, "
      "and lowers the energy") {
    FreeChainProblem problem(20, 0.5);
    Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(20, 0.0, 19.0);
    ProjectedNewton newton;
    newton.options().max_step_length = 0.25;
    newton.options().max_iterations = 20;
    const double start = problem.value(x);
    std::vector<double> energies;
    RecordedSteps recorded;
    const NewtonResult result = newton.minimize(problem, x, recorded);
    for (const SolverStep& step : recorded.steps) energies.push_back(step.energy);
    CHECK(result.status == SolverStatus::kIterationLimit);  // unbounded below: it never ends
    CHECK(result.gradient_descent_steps == 0);
    REQUIRE(energies.size() == 20);
    CHECK(energies.front() < start);
    for (std::size_t i = 1; i < energies.size(); ++i) CHECK(energies[i] < energies[i - 1]);
    // The chain slides as a whole, 0.25 per step at most.
    CHECK(x[0] <= 0.25 * 20 + 1e-9);
    CHECK(x[0] > 0.0);
    CHECK(x.allFinite());
  }
}

TEST_CASE(
    "projected Newton: the damping falls to its floor where the model predicts well and "
    "rises where it does not",
    "[solver][newton][damping]") {
  SECTION("a quadratic: a few full steps, the damping falling") {
    QuadraticProblem problem(40);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(40);
    ProjectedNewton newton;
    newton.options().gradient_tolerance = 1e-10;
    newton.options().step_tolerance = 0.0;
    const NewtonResult result = newton.minimize(problem, x);
    CHECK(result.converged());
    CHECK(result.iterations <= 3);
    CHECK(result.damping < newton.options().initial_damping);
    CHECK((x - problem.solution()).norm() < 1e-8);
  }
  SECTION("Rosenbrock from far away: line-search cuts raise it, convergence lowers it again") {
    RosenbrockProblem problem(3);
    Eigen::VectorXd x(6);
    x << -1.2, 1.0, -1.5, 2.0, 2.0, -1.0;
    ProjectedNewton newton;
    newton.options().gradient_tolerance = 1e-9;
    newton.options().step_tolerance = 0.0;
    std::vector<double> damping{newton.options().initial_damping};
    RecordedSteps recorded;
    const NewtonResult result = newton.minimize(problem, x, recorded);
    for (const SolverStep& step : recorded.steps) damping.push_back(step.damping);
    CAPTURE(result.message);
    CHECK(result.converged());
    int rises = 0;
    for (std::size_t i = 1; i < damping.size(); ++i) rises += damping[i] > damping[i - 1];
    CHECK(rises > 0);
    CHECK(damping.back() == newton.options().min_damping);
    CHECK((x - Eigen::VectorXd::Ones(6)).norm() < 1e-5);
  }
}
