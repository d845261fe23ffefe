#include "retarget/stages/solve_stage.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "retarget/stage_reports.hpp"
#include "retarget/stages/proxy_stage.hpp"
#include "retarget/stages/solve_policy.hpp"

namespace gr {

namespace {

/// Faces of the outfit's largest layer; 0 for a single garment.
int largest_layer_faces(const Scene& scene) {
  if (scene.layers.size() <= 1) return 0;
  std::vector<int> layer_faces(scene.layers.size(), 0);
  for (const int layer : layer_of_garment_faces(scene))
    ++layer_faces[static_cast<std::size_t>(layer)];
  return *std::max_element(layer_faces.begin(), layer_faces.end());
}

/// The solver scene and the inflations run in it, each recorded into the report.
class Inflations {
 public:
  Inflations(const SolveInput& in, const ShrinkOutput& shrink, RetargetReport& report,
             Progress& progress, SolverScene& solver)
      : in_(in), shrink_(shrink), report_(report), progress_(progress), solver_(solver) {}

  /// (Re)builds the solver scene from the current shrink and barrier.
  void build_scene() {
    solver_ = make_solver_scene({in_.scene, in_.normalized, shrink_.shrunk.vertices,
                                 in_.distance_field, in_.inherited, shrink_.pierced_faces},
                                report_.parameters.solver);
    record_modelled(report_, solver_);
  }

  InflationResult inflate(const InflationGuide& guide) {
    InflateOutput inflated =
        run_inflate({solver_}, {report_.parameters.solver, in_.frames, guide}, progress_);
    add_inflation_attempt(report_.inflate, inflated.report);
    record_modelled(report_, solver_);
    report_.seconds.inflate += inflated.seconds;
    progress_.log("inflate", "{} ({:.2f} s)", inflated.inflation.message, report_.seconds.inflate);
    return inflated.inflation;
  }

 private:
  const SolveInput& in_;
  const ShrinkOutput& shrink_;
  RetargetReport& report_;
  Progress& progress_;
  SolverScene& solver_;
};

InflationAttempt attempt_of(const InflationResult& inflation) {
  return {inflation.succeeded(),
          !inflation.succeeded() && inflation.status != InflationStatus::kSolverFailure};
}

/// How many times firmer a second fit holds the pattern (w_fit_stretch).
constexpr double kFirmerPatternFactor = 10.0;

/// How far the scale-free edge changes of `fitted` go beyond the limits: the larger of
/// mean / limit and p95 / limit (above 1: beyond).
double edge_excess(const TriangleMesh& garment, const MatrixX3d& fitted,
                   const ShapeThresholds& limits, ShapeChange& change) {
  change = measure_shape_change(garment, fitted);
  return std::max(change.mean_edge_change / limits.mean_edge_change,
                  change.p95_edge_change / limits.p95_edge_change);
}

}  // namespace

SolveOutput run_solve(const SolveInput& in, ShrinkOutput& shrink, RetargetReport& report,
                      Progress& progress) {
  SolveOutput solved;
  SolverScene& solver = solved.solver;
  Inflations inflations(in, shrink, report, progress, solver);
  inflations.build_scene();
  const RetargetParameters& parameters = report.parameters.solver;
  const SourceEase* source_ease =
      report.ease.fit == FitMode::kEase ? &in.inferred.source_ease : nullptr;
  ProxyOutput proxy =
      run_proxy({solver, source_ease, largest_layer_faces(in.scene)},
                {parameters, report.parameters.proxy_faces, report.ease.max_offset}, progress);
  report.proxy = proxy.report;
  report.seconds.proxy = proxy.report.seconds;
  // A retry below solves the garment directly: the proxy's paths lead where it failed.
  InflationResult inflation =
      inflations.inflate(proxy.paths ? proxy.paths->inflation() : InflationGuide());
  report.proxy.inflate_path = inflation.guide;

  double& dhat = report.parameters.solver.dhat;
  const double first_dhat = dhat;
  SolvePolicy policy(in.shrink_options.mode == ShrinkMode::kSkeleton);
  int pressed = 0;
  const auto pressed_pairs = [&] {
    pressed = pressed_tangle_pairs(solver.scene, parameters, inflation.garment,
                                   SolvePolicy::kPressedGap * parameters.dhat);
    return pressed;
  };
  for (SolveStep step = policy.next(attempt_of(inflation), pressed_pairs);
       step != SolveStep::kFit && step != SolveStep::kGiveUp;
       step = policy.next(attempt_of(inflation), pressed_pairs)) {
    if (step == SolveStep::kThinnerShrink) {
      dhat = first_dhat;
      const double pullback = SolvePolicy::kStalledPullbackFactor * shrink.shrunk.pullback;
      const std::string no_thinner =
          run_thinner_shrink(in.shrink_input, in.shrink_options, pullback, shrink, progress);
      // The shrunk avatar is what failed: one the garment can escape from does not exist.
      if (!no_thinner.empty()) {
        solved.failure = {
            Outcome::kNoValidShrink,
            fmt::format("the inflation from the skeleton shrink (pullback {:.3g}) "
                        "failed: {}; and no thinner shrink is free of the garment: {}",
                        shrink.shrunk.pullback, inflation.message, no_thinner)};
        return solved;
      }
      record_shrink(report, shrink, in.inferred);
    } else {
      const std::string why =
          pressed > 0
              ? fmt::format(", {} pairs pressed together at crossings the input came with", pressed)
              : std::string();
      pressed = 0;
      progress.warn(
          fmt::format("the inflation stalled with dhat {:.3g}{}: inflating again with "
                      "a barrier twice as wide (--dhat {:.3g})",
                      dhat, why, policy.barrier_factor() * first_dhat));
      dhat = policy.barrier_factor() * first_dhat;
    }
    inflations.build_scene();
    inflation = inflations.inflate({});
  }
  if (!inflation.succeeded()) {
    solved.failure = {Outcome::kSolverFailure,
                      "inflation failed: " + inflation.message +
                          "; allow more work with --max-al-rounds and --max-newton-iterations, or "
                          "widen the barrier with --dhat"};
    return solved;
  }
  // A garment whose inflation left the proxy's path starts its fit away from where the
  // proxy's did: held back wherever the two differ, the fit's path would only crumple it.
  const bool guided = proxy.paths && inflation.guide.points > 0 && inflation.guide.reached_end;
  solved.fit = run_fit({solver, inflation.garment, source_ease},
                       {parameters, report.ease.max_offset,
                        guided ? proxy.paths->fit(inflation.garment) : GuidePath()},
                       progress);
  // A tight fit can pull a garment's pattern out of shape (a heeled shoe onto a flat
  // foot): beyond the run's edge limits, the fit runs again from the same inflated garment
  // holding the pattern firmer, and the result that keeps it better is kept.
  ShapeChange first;
  if (in.shape_thresholds.enabled && in.scene.source_skeleton && parameters.w_fit_stretch > 0.0 &&
      edge_excess(in.normalized.garment, solved.fit.fit.garment, in.shape_thresholds, first) >
          1.0) {
    FitOptions firmer{parameters, report.ease.max_offset, {}};
    firmer.parameters.w_fit_stretch *= kFirmerPatternFactor;
    progress.log("fit",
                 "edge change mean {:.3f}, p95 {:.3f} beyond the shape limits: fitting again "
                 "holding the pattern firmer (w_fit_stretch {:.3g})",
                 first.mean_edge_change, first.p95_edge_change, firmer.parameters.w_fit_stretch);
    FitOutput again = run_fit({solver, inflation.garment, source_ease}, firmer, progress);
    ShapeChange second;
    if (edge_excess(in.normalized.garment, again.fit.garment, in.shape_thresholds, second) <
        edge_excess(in.normalized.garment, solved.fit.fit.garment, in.shape_thresholds, first)) {
      solved.fit = std::move(again);
      solved.fit.report.firmer_pattern = true;
      solved.fit.report.first_mean_edge_change = first.mean_edge_change;
      solved.fit.report.first_p95_edge_change = first.p95_edge_change;
    }
  }
  report.proxy.fit_path = solved.fit.fit.guide;
  if (solved.fit.ease_targets) report.ease.targets = std::move(*solved.fit.ease_targets);
  report.fit = solved.fit.report;
  record_modelled(report, solver);
  report.seconds.fit = solved.fit.seconds;
  const NewtonResult& solve = solved.fit.fit.solve;
  if (solve.status == SolverStatus::kNonFiniteEnergy || !std::isfinite(solve.gradient_norm))
    solved.failure = {Outcome::kSolverFailure, "fit failed: " + solve.message};
  return solved;
}

}  // namespace gr
