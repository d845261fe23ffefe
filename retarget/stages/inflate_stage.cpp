#include "retarget/stages/inflate_stage.hpp"

#include <fmt/format.h>

namespace gr {

InflateOutput run_inflate(const InflateInput& input, const InflateOptions& options,
                          Progress& progress) {
  const StageTimer timer;
  SolverScene& solver = input.solver;
  const MatrixX3d& shrunk = solver.scene.shrunk_avatar;
  const MatrixX3d& avatar = solver.scene.avatar.vertices;
  if (options.write_frame) options.write_frame("round_00", solver.scene.garment.vertices, shrunk);
  const auto on_round = [&](const InflationRound& round) {
    progress.log(
        "inflate", "round {:2d}: t {:.9f}  eta {:.3g}  lambda1 {:.3g}  {} Newton steps{}{}",
        round.round, round.t, round.eta, round.lambda1, round.solve.iterations,
        round.reset ? "  (overshoot: reset)" : "", round.snapped ? "  snap to t = 1 valid" : "");
    if (options.write_frame)
      options.write_frame(fmt::format("round_{:02d}", round.round), round.garment,
                          shrunk + round.t * (avatar - shrunk));
  };
  progress.start("inflate");
  InflateOutput out;
  out.inflation =
      inflate_avatar(solver.scene, options.parameters, on_round, progress, options.guide);
  if (out.inflation.succeeded() &&
      widen_scope_if_left(solver, out.inflation.garment, options.parameters.dhat, "inflation",
                          progress))
    out.inflation =
        inflate_avatar(solver.scene, options.parameters, on_round, progress, options.guide);
  const InflationResult& inflation = out.inflation;
  if (inflation.guide.points > 0)
    progress.log("inflate", "{}", describe_following(inflation.guide));
  out.report.al_rounds = inflation.rounds;
  out.report.resets = inflation.resets;
  out.report.newton_iterations = inflation.newton_iterations;
  out.report.factorizations = inflation.factorizations;
  out.report.fold_free = inflation.fold_free_fraction;
  out.report.status = to_string(inflation.status);
  out.seconds = timer.seconds();
  return out;
}

void add_inflation_attempt(InflateReport& total, const InflateReport& attempt) {
  total.al_rounds += attempt.al_rounds;
  total.resets += attempt.resets;
  total.newton_iterations += attempt.newton_iterations;
  total.factorizations += attempt.factorizations;
  total.fold_free = attempt.fold_free;
  total.status = attempt.status;
}

}  // namespace gr
