#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "core/common/interrupter.hpp"
#include "core/solver/projected_newton.hpp"

using namespace gr;

namespace {

/// (x - 1)² per dof, with every step capped at a hundredth of the Newton step: hundreds of
/// steps, each lowering the energy a little.
class CreepingProblem : public Problem {
 public:
  int dof_count() const override { return 3; }
  double value(const Eigen::VectorXd& x) override { return (x.array() - 1.0).square().sum(); }
  void gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) override {
    g = 2.0 * (x.array() - 1.0).matrix();
  }
  void hessian(const Eigen::VectorXd& x, Eigen::SparseMatrix<double>& H) override {
    H.resize(x.size(), x.size());
    H.setIdentity();
    H *= 2.0;
  }
  double max_step(const Eigen::VectorXd&, const Eigen::VectorXd&) override { return 0.01; }
};

/// Stops with a timeout once it has seen `limit` steps, naming its stage.
class StopAfterSteps : public Interrupter {
 public:
  explicit StopAfterSteps(std::size_t limit) : limit_(limit) {}
  void start(const std::string& stage) override { stage_ = stage; }
  void step(const SolverStep& step) override { steps.push_back(step); }
  std::optional<Interrupted> interruption() const override {
    if (steps.size() < limit_) return std::nullopt;
    return Interrupted(InterruptReason::kTimeout, "timed out during " + stage_);
  }
  std::vector<SolverStep> steps;

 private:
  std::size_t limit_;
  std::string stage_;
};

}  // namespace

TEST_CASE("projected Newton: an interrupter stops the solve after the steps it allows",
          "[solver][newton][interrupter]") {
  const std::size_t allowed = GENERATE(1, 2, 7);
  CAPTURE(allowed);
  CreepingProblem problem;
  NewtonOptions options;
  options.max_iterations = 5000;
  ProjectedNewton newton(options);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(3);
  StopAfterSteps interrupter(allowed);
  interrupter.start("creep");
  try {
    newton.minimize(problem, x, interrupter);
    FAIL("the solve was not interrupted");
  } catch (const Interrupted& stopped) {
    CHECK(stopped.reason() == InterruptReason::kTimeout);
    CHECK(std::string(stopped.what()) == "timed out during creep");
  }
  // Every step before the stop was reported, numbered, with its falling energy.
  REQUIRE(interrupter.steps.size() == allowed);
  double energy = problem.value(Eigen::VectorXd::Zero(3));
  for (std::size_t i = 0; i < allowed; ++i) {
    CHECK(interrupter.steps[i].iteration == static_cast<int>(i) + 1);
    CHECK(interrupter.steps[i].energy < energy);
    CHECK(interrupter.steps[i].step > 0.0);
    energy = interrupter.steps[i].energy;
  }
  // x holds the step accepted just before the stop: one beyond the last one reported.
  CHECK(problem.value(x) < energy);
  CHECK(x.allFinite());
}

TEST_CASE("projected Newton: without an interrupter the same solve runs to its end",
          "[solver][newton][interrupter]") {
  CreepingProblem problem;
  NewtonOptions options;
  options.max_iterations = 5000;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(3);
  const NewtonResult result = ProjectedNewton(options).minimize(problem, x);
  CHECK(result.converged());
  CHECK(result.iterations > 7);
  CHECK_FALSE(null_interrupter().was_interrupted());
}

TEST_CASE("interrupter: a forwarding adaptor passes stages, steps and the stop on",
          "[interrupter]") {
  StopAfterSteps inner(1);
  ForwardingInterrupter outer(inner);
  outer.start("outer stage");
  CHECK_FALSE(outer.was_interrupted());
  outer.step({});
  CHECK(inner.steps.size() == 1);
  REQUIRE(outer.was_interrupted());
  CHECK_THROWS_WITH(outer.check(), "timed out during outer stage");
}
