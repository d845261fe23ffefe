#include "core/solver/projected_newton.hpp"

#include <cmath>
#include <deque>

#include <fmt/format.h>

#include "core/common/stopwatch.hpp"

namespace gr {

namespace {
/// The Newton-step convergence test applies while mu is within this factor of its floor.
constexpr double kTrustedDamping = 100.0;
}  // namespace

const char* to_string(SolverStatus status) {
  switch (status) {
    case SolverStatus::kConverged: return "converged";
    case SolverStatus::kIterationLimit: return "iteration limit";
    case SolverStatus::kNoDescent: return "no descent";
    case SolverStatus::kNonFiniteEnergy: return "non-finite energy";
    case SolverStatus::kGoalReached: return "goal reached";
  }
  return "unknown";
}

namespace {

/// Marquardt's scaling: H's diagonal, floored so that every dof is damped (a vertex no term
/// holds has a zero diagonal).
Eigen::VectorXd damping_scale(const Eigen::SparseMatrix<double>& H) {
  Eigen::VectorXd diagonal = H.diagonal().cwiseAbs();
  const double mean = diagonal.size() > 0 ? diagonal.mean() : 0.0;
  constexpr double kRelativeFloor = 1e-10;
  const double floor = mean > 0.0 && std::isfinite(mean) ? kRelativeFloor * mean : 1.0;
  return diagonal.cwiseMax(floor);
}

}  // namespace

bool ProjectedNewton::damped_direction(Problem& problem, const Eigen::SparseMatrix<double>& H,
                                       const Eigen::VectorXd& g, Eigen::VectorXd& direction,
                                       NewtonResult& result) {
  const Eigen::VectorXd scale = damping_scale(H);
  if (!reused_factor_direction(H, g, scale, direction, result) &&
      !factored_direction(H, g, scale, direction, result))
    return false;
  clip_to_trust_radius(problem, direction);
  return true;
}

bool ProjectedNewton::reused_factor_direction(const Eigen::SparseMatrix<double>& H,
                                              const Eigen::VectorXd& g,
                                              const Eigen::VectorXd& scale,
                                              Eigen::VectorXd& direction, NewtonResult& result) {
  if (!(options_.reuse_factor_flops > 0.0) || !linear_solver_.has_factor(H.rows()) ||
      linear_solver_.factorization_flops() < options_.reuse_factor_flops)
    return false;
  if (reuse_skips_left_ > 0) {
    --reuse_skips_left_;
    return false;
  }
  const int iterations = linear_solver_.solve_preconditioned(
      H, damping_ * scale, -g, options_.reuse_tolerance, options_.reuse_max_iterations, direction);
  if (iterations < 0 || !direction.allFinite() || !(direction.dot(g) < 0.0)) {
    // Where the Hessian changes fast (pairs entering the barrier) the held factor stops
    // helping: skip the attempt for 1, 2, 4... steps after failures in a row, so that a
    // solve that never reuses wastes only a logarithmic number of them.
    reuse_skips_left_ = reuse_skips_after_failure_;
    reuse_skips_after_failure_ = std::max(1, 2 * reuse_skips_after_failure_);
    return false;
  }
  reuse_skips_after_failure_ = 0;
  ++result.reused_factor_steps;
  result.cg_iterations += iterations;
  return true;
}

bool ProjectedNewton::factored_direction(const Eigen::SparseMatrix<double>& H,
                                         const Eigen::VectorXd& g, const Eigen::VectorXd& scale,
                                         Eigen::VectorXd& direction, NewtonResult& result) {
  // A factorization can still fail where rounding meets stiffnesses far apart: more
  // damping then, up to max_damping.
  constexpr double kFailureGrowth = 100.0;
  for (;;) {
    ++result.factorizations;
    if (linear_solver_.factorize(H, damping_ * scale)) {
      direction = -linear_solver_.solve(g);
      if (direction.allFinite() && direction.dot(g) < 0.0) return true;
    }
    if (damping_ >= options_.max_damping) return false;
    damping_ = std::min(kFailureGrowth * damping_, options_.max_damping);
  }
}

void ProjectedNewton::clip_to_trust_radius(Problem& problem, Eigen::VectorXd& direction) const {
  const double length = problem.step_length(direction);
  if (length > options_.max_step_length) direction *= options_.max_step_length / length;
}

void ProjectedNewton::update_damping(double ratio) {
  if (ratio > 0.0) {
    const double cube = (2.0 * ratio - 1.0) * (2.0 * ratio - 1.0) * (2.0 * ratio - 1.0);
    damping_ = std::max(damping_ * std::max(1.0 / 3.0, 1.0 - cube), options_.min_damping);
    damping_growth_ = 2.0;
  } else {
    damping_ = std::min(damping_ * damping_growth_, options_.max_damping);
    damping_growth_ *= 2.0;
  }
}

NewtonResult ProjectedNewton::minimize(Problem& problem, Eigen::VectorXd& x,
                                       Interrupter& interrupter) {
  const Stopwatch stopwatch;
  const auto elapsed = [&stopwatch] { return stopwatch.seconds(); };
  NewtonResult result;
  linear_solver_.set_pattern_slack(options_.pattern_slack);
  const double sqrt_dofs = std::sqrt(static_cast<double>(std::max(problem.dof_count(), 1)));
  const auto finish = [&](SolverStatus status, std::string message) {
    result.status = status;
    result.message = std::move(message);
    result.elapsed_seconds = elapsed();
    result.damping = damping_;
    return result;
  };

  problem.solution_changed(x);
  double energy = problem.value(x);
  result.energy = energy;
  if (!std::isfinite(energy))
    return finish(SolverStatus::kNonFiniteEnergy, "the energy at the start point is not finite");

  Eigen::VectorXd g, direction, trial;
  Eigen::SparseMatrix<double> H;
  if (damping_ < 0.0) damping_ = std::max(options_.initial_damping, options_.min_damping);
  // Energies at the last energy_window + 1 accepted points, the current one last.
  std::deque<double> recent_energies{energy};
  const double start_energy = energy;
  for (;;) {
    if (problem.goal_reached(x))
      return finish(SolverStatus::kGoalReached,
                    fmt::format("the problem's goal is met after {} steps", result.iterations));
    problem.gradient(x, g);
    result.gradient_norm = g.norm();
    if (!g.allFinite())
      return finish(SolverStatus::kNonFiniteEnergy,
                    fmt::format("the gradient is not finite after {} steps", result.iterations));
    if (result.gradient_norm / sqrt_dofs <= options_.gradient_tolerance)
      return finish(SolverStatus::kConverged,
                    fmt::format("RMS gradient {:.3g} <= {:.3g} after {} steps",
                                result.gradient_norm / sqrt_dofs, options_.gradient_tolerance,
                                result.iterations));
    if (result.iterations >= options_.max_iterations)
      return finish(SolverStatus::kIterationLimit,
                    fmt::format("{} steps without converging (RMS gradient {:.3g})",
                                result.iterations, result.gradient_norm / sqrt_dofs));

    const int window = options_.energy_window;
    if (options_.energy_tolerance > 0.0 && window > 0 &&
        static_cast<int>(recent_energies.size()) > window) {
      const double decrease = recent_energies.front() - energy;
      const double reference = std::min(std::abs(energy), start_energy - energy);
      if (decrease <= options_.energy_tolerance * reference)
        return finish(SolverStatus::kConverged,
                      fmt::format("energy fell by {:.3g} (relative {:.3g} <= {:.3g}) over the last "
                                  "{} steps, after {} steps",
                                  decrease, decrease / reference, options_.energy_tolerance, window,
                                  result.iterations));
    }

    problem.hessian(x, H);
    if (damped_direction(problem, H, g, direction, result)) {
      result.newton_step_length = problem.step_length(direction);
      // A short step says the minimizer is near only when the damping is too small to
      // have shortened it.
      if (result.newton_step_length <= options_.step_tolerance &&
          damping_ <= kTrustedDamping * options_.min_damping)
        return finish(
            SolverStatus::kConverged,
            fmt::format("Newton step {:.3g} <= {:.3g} after {} steps", result.newton_step_length,
                        options_.step_tolerance, result.iterations));
    } else {
      direction = -g;
      ++result.gradient_descent_steps;
      clip_to_trust_radius(problem, direction);
    }
    double alpha = std::min(1.0, problem.max_step(x, direction));
    if (!(alpha > 0.0))
      return finish(
          SolverStatus::kNoDescent,
          fmt::format("no safe step along the search direction after {} steps", result.iterations));
    // The problem may model this motion differently from the last one (a contact model that
    // leaves out pairs which cannot touch along it): compare trials with its energy at x.
    energy = problem.value(x);
    double trial_energy = 0.0;
    bool accepted = false;
    // The quadratic model's decrease along the direction: -(alpha g.p + alpha^2/2 p.Hp).
    const double slope = g.dot(direction);
    const double curvature = direction.dot(H * direction);
    int halvings = 0;
    for (; halvings <= options_.max_line_search_halvings; ++halvings, alpha *= 0.5) {
      trial = x + alpha * direction;
      trial_energy = problem.value(trial);
      if (std::isfinite(trial_energy) && trial_energy <= energy && problem.is_valid(trial)) {
        accepted = true;
        break;
      }
    }
    // The step taken judges the model: its actual decrease against the quadratic model's
    // prediction for that same step, also when the line search cut it. Counting a cut step
    // as a failed prediction instead raised mu on every cut, and more on each in a row
    // (Nielsen's nu), and near contact, where pairs entering the barrier cut steps often,
    // the steps crept (bench/results/parameter_choices.md).
    if (accepted) {
      const double predicted = -(alpha * slope + 0.5 * alpha * alpha * curvature);
      update_damping(predicted > 0.0 ? (energy - trial_energy) / predicted : 0.0);
    } else {
      update_damping(0.0);
    }
    if (!accepted)
      return finish(
          SolverStatus::kNoDescent,
          fmt::format("line search found no decrease after {} steps (RMS gradient {:.3g})",
                      result.iterations, result.gradient_norm / sqrt_dofs));

    x.swap(trial);
    energy = trial_energy;
    ++result.iterations;
    result.energy = energy;
    recent_energies.push_back(energy);
    if (static_cast<int>(recent_energies.size()) > options_.energy_window + 1)
      recent_energies.pop_front();
    problem.solution_changed(x);
    interrupter.check();
    interrupter.step(
        {result.iterations, energy, alpha, result.gradient_norm, elapsed(), damping_, &x});
  }
}

}  // namespace gr
