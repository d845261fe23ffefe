#pragma once

#include <functional>
#include <string>

#include "core/inflation/avatar_inflation.hpp"
#include "retarget/report.hpp"
#include "retarget/run/progress.hpp"
#include "retarget/stages/solver_scene.hpp"

namespace gr {

/// Writes one intermediate state (normalized garment #Vg×3 and avatar #Va×3) named
/// "round_NN".
using FrameWriter =
    std::function<void(const std::string& name, const MatrixX3d& garment, const MatrixX3d& avatar)>;

struct InflateInput {
  /// The solver's scene; its contact scope widens to every avatar face when the solve
  /// carried the garment beyond it (the inflation then runs again).
  SolverScene& solver;
};

struct InflateOptions {
  RetargetParameters parameters;
  FrameWriter write_frame;  ///< empty: no frames
  /// Where a coarse proxy's inflation says the garment goes (coarse to fine); empty path:
  /// none.
  InflationGuide guide;
};

struct InflateOutput {
  InflationResult inflation;
  InflateReport report;
  double seconds = 0.0;
};

/// Inflate: the avatar grows back from the shrunk avatar to the avatar under barrier
/// contact (Algorithm 1), every step CCD-bounded.
/// @throw Interrupted from progress (the run's limits).
InflateOutput run_inflate(const InflateInput& input, const InflateOptions& options,
                          Progress& progress);

/// `attempt`'s report added to `total` (counts add up; status and fold-free share are the
/// last attempt's).
void add_inflation_attempt(InflateReport& total, const InflateReport& attempt);

}  // namespace gr
