#pragma once

#include <optional>
#include <string>
#include <utility>

#include "core/energies/distance_field.hpp"
#include "retarget/outcome.hpp"
#include "retarget/report.hpp"
#include "retarget/stages/fit_stage.hpp"
#include "retarget/stages/infer_stage.hpp"
#include "retarget/stages/inflate_stage.hpp"
#include "retarget/stages/shrink_stage.hpp"
#include "retarget/stages/solver_scene.hpp"
#include "validate/measure/shape_change.hpp"

namespace gr {

/// What the solve needs from the stages before it.
struct SolveInput {
  const Scene& scene;
  const NormalizedScene& normalized;
  const InheritedCrossings& inherited;
  const ShrinkInput& shrink_input;
  const ShrinkOptions& shrink_options;
  const DistanceField& distance_field;  ///< the shrink's grid
  const InferOutput& inferred;
  FrameWriter frames;  ///< empty: no frames
  /// The run's shape limits: a fit whose edges change beyond them is tried again holding
  /// the pattern firmer (with skeletons, where the fit holds the pattern).
  ShapeThresholds shape_thresholds{};
};

/// The solved garment, or how the solve failed.
struct SolveOutput {
  std::optional<std::pair<Outcome, std::string>> failure;
  SolverScene solver;
  FitOutput fit;
};

/// The solve: the coarse proxy where the garment is dense, the inflation, retried as
/// SolvePolicy says when it stalls (a wider barrier; a thinner skeleton shrink, which
/// replaces `shrink`), then the fit (again holding the pattern firmer where the first
/// changes edges beyond the shape limits). Records its parts of `report` (proxy, inflate, fit,
/// the barrier it ended with) as it goes.
/// @throw Interrupted from progress (the run's limits).
SolveOutput run_solve(const SolveInput& input, ShrinkOutput& shrink, RetargetReport& report,
                      Progress& progress);

}  // namespace gr
