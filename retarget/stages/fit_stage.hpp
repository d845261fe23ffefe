#pragma once

#include <optional>

#include "core/fit/garment_fit.hpp"
#include "garment/fit/ease.hpp"
#include "retarget/report.hpp"
#include "retarget/run/progress.hpp"
#include "retarget/stages/solver_scene.hpp"

namespace gr {

struct FitInput {
  /// The solver's scene; its contact scope widens to every avatar face when the fit
  /// carried the garment beyond it (the fit then runs again), and the ease fit sets its
  /// offsets.
  SolverScene& solver;
  const MatrixX3d& inflated;  ///< the inflation's garment (#Vg×3), free of the avatar
  /// The garment's ease on its source body for the ease fit; null: the tight fit.
  const SourceEase* source_ease = nullptr;
};

struct FitOptions {
  RetargetParameters parameters;
  double max_ease_offset = 0.0;  ///< the largest ease target the distance band holds
  GuidePath guide;               ///< where a coarse proxy's fit says the garment goes; empty: none
};

struct FitOutput {
  FitResult fit;
  /// The ease fit's targets (EaseTargets::offsets moved into the solver scene).
  std::optional<EaseTargets> ease_targets;
  FitReport report;
  double seconds = 0.0;
};

/// Fit: the garment settles onto the body (Step 3), onto the avatar (tight) or at its
/// source ease scaled as the garment is (ease), with the end-of-fit measurements in its
/// report part. A fit stopped early is still intersection-free (every step was
/// CCD-bounded) and warns.
/// @throw Interrupted from progress (the run's limits).
FitOutput run_fit(const FitInput& input, const FitOptions& options, Progress& progress);

}  // namespace gr
