#include "core/inflation/avatar_inflation.hpp"

#include <cmath>

#include <fmt/format.h>

#include "core/common/stopwatch.hpp"

namespace gr {
namespace {
/// A round stalls when t gains less than this fraction of its remaining distance to 1.
constexpr double kStalledProgress = 0.01;
}  // namespace

const char* to_string(InflationStatus status) {
  switch (status) {
    case InflationStatus::kSnapped: return "snapped";
    case InflationStatus::kRoundLimit: return "round limit";
    case InflationStatus::kStalled: return "stalled";
    case InflationStatus::kSolverFailure: return "solver failure";
  }
  return "unknown";
}

InflationResult inflate_avatar(const GarmentScene& scene, const RetargetParameters& parameters,
                               const InflationCallback& on_round, Interrupter& interrupter,
                               const InflationGuide& guide) {
  const Stopwatch stopwatch;
  GarmentProblem problem(scene, parameters, GarmentProblem::Stage::kInflation);
  const DofLayout& layout = problem.layout();
  AvatarConstraint& al = problem.constraint();
  NewtonOptions newton_options = parameters.newton;
  newton_options.max_step_length = parameters.inflation_step_length;
  ProjectedNewton newton(newton_options);

  const Eigen::VectorXd initial = layout.pack(0.0, scene.garment.vertices);
  Eigen::VectorXd x = initial;
  InflationResult result;
  if (guide.path.size > 0) result.guide = follow_guide(problem, x, guide.path, newton_options);
  if (guide.lambda1 > 0.0) {
    al.lambda1 = guide.lambda1;
    al.lambda2 = guide.lambda2;
  }
  const auto finish = [&](InflationStatus status, std::string message) {
    result.status = status;
    result.message = std::move(message);
    result.garment = layout.garment(x);
    result.t = layout.t(x);
    result.lambda1 = al.lambda1;
    result.lambda2 = al.lambda2;
    result.fold_free_fraction = problem.contact().mean_fold_free_fraction();
    result.elapsed_seconds = stopwatch.seconds();
    return result;
  };

  int stalled_rounds = 0;
  while (result.rounds < parameters.max_al_rounds) {
    ++result.rounds;
    problem.tether_to(x);
    const double t_before = layout.t(x);
    const NewtonResult solve = newton.minimize(problem, x, interrupter);
    result.newton_iterations += solve.iterations;
    result.factorizations += solve.factorizations;
    if (solve.status == SolverStatus::kNonFiniteEnergy)
      return finish(InflationStatus::kSolverFailure,
                    fmt::format("round {}: {}", result.rounds, solve.message));

    InflationRound round{result.rounds, layout.t(x), 0.0, 0.0, 0.0, false, false, solve, {}};
    round.eta = 1.0 - std::sqrt(std::abs(1.0 - round.t));
    if (on_round) round.garment = layout.garment(x);
    // A reset is the augmented Lagrangian's own remedy (t overshot), not a pinch.
    const bool gained = round.t - t_before >= kStalledProgress * (1.0 - t_before);
    stalled_rounds = gained || round.eta < 0.0 ? 0 : stalled_rounds + 1;
    if (round.eta < 0.0) {
      x = initial;
      al.lambda1 *= 2.0;
      round.reset = true;
      ++result.resets;
    }
    const double t = layout.t(x);
    if (round.eta < parameters.eta_target && al.lambda1 < parameters.max_lambda1)
      al.lambda1 *= 2.0;
    else
      al.update_multiplier(t);
    round.lambda1 = al.lambda1;
    round.lambda2 = al.lambda2;
    // A solve that ended at its goal has just checked this snap at x.
    round.snapped = solve.status == SolverStatus::kGoalReached || problem.is_valid_snapping(x);
    interrupter.check();
    if (on_round) on_round(round);
    if (round.snapped) {
      result.t_before_snap = t;
      if (layout.t_free) x[layout.t_index()] = 1.0;
      return finish(
          InflationStatus::kSnapped,
          fmt::format("snapped to t = 1 from t = {:.9g} after {} rounds ({} Newton steps)", t,
                      result.rounds, result.newton_iterations));
    }
    if (stalled_rounds >= parameters.max_stalled_rounds)
      return finish(InflationStatus::kStalled,
                    fmt::format("stalled at t = {:.6g}: t gained less than {:g} of its remaining "
                                "distance to 1 in {} rounds in a row",
                                round.t, kStalledProgress, stalled_rounds));
  }
  return finish(InflationStatus::kRoundLimit,
                fmt::format("no collision-free snap to t = 1 after {} rounds (t = {:.6g})",
                            result.rounds, layout.t(x)));
}

}  // namespace gr
