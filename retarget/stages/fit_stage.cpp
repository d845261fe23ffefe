#include "retarget/stages/fit_stage.hpp"

#include <fmt/format.h>

namespace gr {

namespace {

/// A boundary loop further than this (in lengths of its bone) from its place along the bone
/// on the written garment is reported: the loops of a fitted garment sit within a few
/// thousandths of theirs.
constexpr double kLoopOffsetWarning = 0.03;

double surface_area(const TriangleMesh& mesh) {
  double area = 0.0;
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    const Vector3d a = mesh.vertices.row(mesh.faces(f, 0)).transpose();
    const Vector3d b = mesh.vertices.row(mesh.faces(f, 1)).transpose();
    const Vector3d c = mesh.vertices.row(mesh.faces(f, 2)).transpose();
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  return area;
}

}  // namespace

FitOutput run_fit(const FitInput& input, const FitOptions& options, Progress& progress) {
  SolverScene& solver = input.solver;
  FitOutput out;
  if (input.source_ease) {
    EaseTargets targets = ease_targets(solver.scene.garment, input.inflated, *input.source_ease,
                                       options.max_ease_offset);
    solver.scene.fit_offsets = std::move(targets.offsets);
    out.ease_targets = std::move(targets);
    progress.log("fit",
                 "ease kept: local scale {:.3g} to {:.3g} (median {:.3g}), {} targets "
                 "capped",
                 out.ease_targets->min_scale, out.ease_targets->max_scale,
                 out.ease_targets->median_scale, out.ease_targets->capped);
  }
  const StageTimer timer;
  progress.start("fit");
  const RetargetParameters& parameters = options.parameters;
  out.fit = fit_garment(solver.scene, input.inflated, parameters, progress, options.guide);
  if (out.fit.guide.points > 0) progress.log("fit", "{}", describe_following(out.fit.guide));
  if (out.fit.solve.status != SolverStatus::kNonFiniteEnergy &&
      widen_scope_if_left(solver, out.fit.garment, parameters.dhat, "fit", progress))
    out.fit = fit_garment(solver.scene, input.inflated, parameters, progress, options.guide);
  const FitResult& fit = out.fit;
  FitReport& report = out.report;
  report.newton_iterations = fit.solve.iterations;
  report.factorizations = fit.solve.factorizations;
  report.fold_free = fit.fold_free_fraction;
  report.status = to_string(fit.solve.status);
  out.seconds = timer.seconds();
  progress.log("fit", "{} after {} Newton steps ({:.2f} s)", fit.solve.message,
               fit.solve.iterations, out.seconds);
  if (fit.solve.status == SolverStatus::kNonFiniteEnergy) return out;
  if (!fit.solve.converged())
    progress.warn("fit stopped before its tolerance: " + fit.solve.message +
                  "; allow more steps with --max-newton-iterations or loosen --eps-tol");
  report.terms = fit.terms;
  report.min_distance = fit.min_distance;
  report.energies = fit.energies;
  report.loop_offsets = fit.loop_offsets;
  for (std::size_t loop = 0; loop < fit.loop_offsets.size(); ++loop) {
    if (fit.loop_offsets[loop] <= kLoopOffsetWarning) continue;
    progress.warn(fmt::format(
        "boundary loop {} ({} vertices) ends {:.0f}% of its bone's length from its place along "
        "the bone: it may be caught on the avatar and the garment stretched around it",
        loop, fit.loop_sizes[loop], 100.0 * fit.loop_offsets[loop]));
  }
  const auto surface = fit.energies.find("surface");
  report.surface_energy_per_area =
      (surface != fit.energies.end() ? surface->second : 0.0) / surface_area(solver.scene.garment);
  return out;
}

}  // namespace gr
