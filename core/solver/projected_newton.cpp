#include "core/solver/projected_newton.hpp"

#include <chrono>
#include <cmath>
#include <deque>

#include <fmt/format.h>

namespace gr {

const char* to_string(SolverStatus status) {
  switch (status) {
    case SolverStatus::kConverged: return "converged";
    case SolverStatus::kIterationLimit: return "iteration limit";
    case SolverStatus::kNoDescent: return "no descent";
    case SolverStatus::kNonFiniteEnergy: return "non-finite energy";
  }
  return "unknown";
}

bool ProjectedNewton::newton_direction(const Eigen::SparseMatrix<double>& H,
                                       const Eigen::VectorXd& g, Eigen::VectorXd& direction) {
  const double diagonal_scale =
      H.rows() > 0 ? H.diagonal().cwiseAbs().sum() / static_cast<double>(H.rows()) : 0.0;
  double shift = 0.0;
  for (int attempt = 0; attempt <= options_.shift_retries; ++attempt) {
    if (linear_solver_.factorize(H, shift)) {
      direction = -linear_solver_.solve(g);
      // A nearly singular factor can still produce garbage: require a descent direction.
      if (direction.allFinite() && direction.dot(g) < 0.0) return true;
    }
    shift = shift == 0.0 ? options_.first_shift * std::max(diagonal_scale, 1e-300) : 100.0 * shift;
  }
  return false;
}

NewtonResult ProjectedNewton::minimize(Problem& problem, Eigen::VectorXd& x,
                                       const NewtonCallback& progress) {
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&start] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  NewtonResult result;
  linear_solver_.set_pattern_slack(options_.pattern_slack);
  const double sqrt_dofs = std::sqrt(static_cast<double>(std::max(problem.dof_count(), 1)));
  const auto finish = [&](SolverStatus status, std::string message) {
    result.status = status;
    result.message = std::move(message);
    result.elapsed_seconds = elapsed();
    return result;
  };

  problem.solution_changed(x);
  double energy = problem.value(x);
  result.energy = energy;
  if (!std::isfinite(energy))
    return finish(SolverStatus::kNonFiniteEnergy, "the energy at the start point is not finite");

  Eigen::VectorXd g, direction, trial;
  Eigen::SparseMatrix<double> H;
  // Energies at the last energy_window + 1 accepted points, the current one last.
  std::deque<double> recent_energies{energy};
  const double start_energy = energy;
  for (;;) {
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
                                  decrease, decrease / reference, options_.energy_tolerance,
                                  window, result.iterations));
    }

    problem.hessian(x, H);
    const bool newton = newton_direction(H, g, direction);
    if (newton) {
      result.newton_step_length = problem.step_length(direction);
      if (result.newton_step_length <= options_.step_tolerance)
        return finish(SolverStatus::kConverged,
                      fmt::format("Newton step {:.3g} <= {:.3g} after {} steps",
                                  result.newton_step_length, options_.step_tolerance,
                                  result.iterations));
    } else {
      direction = -g;
      ++result.gradient_descent_steps;
    }
    const double length = problem.step_length(direction);
    if (length > options_.max_step_length) direction *= options_.max_step_length / length;

    double alpha = std::min(1.0, problem.max_step(x, direction));
    if (!(alpha > 0.0))
      return finish(SolverStatus::kNoDescent,
                    fmt::format("no safe step along the search direction after {} steps",
                                result.iterations));
    // The problem may model this motion differently from the last one (a contact model that
    // leaves out pairs which cannot touch along it): compare trials with its energy at x.
    energy = problem.value(x);
    double trial_energy = 0.0;
    bool accepted = false;
    for (int halving = 0; halving <= options_.max_line_search_halvings; ++halving, alpha *= 0.5) {
      trial = x + alpha * direction;
      trial_energy = problem.value(trial);
      if (std::isfinite(trial_energy) && trial_energy <= energy && problem.is_valid(trial)) {
        accepted = true;
        break;
      }
    }
    if (!accepted)
      return finish(SolverStatus::kNoDescent,
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
    if (progress) progress({result.iterations, energy, alpha, result.gradient_norm, elapsed()});
  }
}

}  // namespace gr
