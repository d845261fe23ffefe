#pragma once

#include <functional>
#include <string>

#include "core/inflation/garment_problem.hpp"
#include "core/solver/guide_path.hpp"

namespace gr {

enum class InflationStatus {
  kSnapped,     ///< t reached 1 exactly with a collision-free snap
  kRoundLimit,  ///< max_al_rounds Newton solves without a valid snap
  /// t stopped growing for max_stalled_rounds rounds in a row: the garment is caught
  /// between parts of the growing avatar
  kStalled,
  kSolverFailure,  ///< a Newton solve met a non-finite energy
};

const char* to_string(InflationStatus status);

/// Reported after each augmented Lagrangian round (one Newton solve).
struct InflationRound {
  int round;                ///< 1-based
  double t;                 ///< after the solve (before any reset)
  double eta;               ///< 1 - sqrt(|1 - t|)
  double lambda1, lambda2;  ///< after this round's update
  bool reset;               ///< eta < 0: garment and t went back to the start
  bool snapped;             ///< the snap to t = 1 is collision free
  NewtonResult solve;
  MatrixX3d garment;  ///< #Vg×3 after the solve (before any reset)
};

using InflationCallback = std::function<void(const InflationRound&)>;

struct InflationResult {
  InflationStatus status = InflationStatus::kRoundLimit;
  MatrixX3d garment;  ///< #Vg×3; with kSnapped, free of the avatar A at t = 1
  double t = 0.0;     ///< 1 exactly when snapped; else the last t
  double t_before_snap = 0.0;
  int rounds = 0;
  int newton_iterations = 0;  ///< summed over rounds
  int factorizations = 0;     ///< Cholesky factorizations, summed over rounds
  int resets = 0;
  /// Mean fraction of garment faces whose self-contact was left out as fold free per step.
  double fold_free_fraction = 0.0;
  double lambda1 = 0.0, lambda2 = 0.0;
  double elapsed_seconds = 0.0;
  GuideFollowed guide;  ///< how far the guide led (no points without one)
  std::string message;
  bool succeeded() const { return status == InflationStatus::kSnapped; }
};

/// Where a coarse solve of the same scene says the inflation goes.
struct InflationGuide {
  GuidePath path;        ///< [t, Vg] points the garment passes through before the first round
  double lambda1 = 0.0;  ///< the augmented Lagrangian's start; 0: the parameters' own
  double lambda2 = 0.0;
};

/// Step 2, Algorithm 1: augmented Lagrangian on t = 1 over x = [t, Vg], starting from the
/// initial garment and t = 0 (the shrunk avatar). Each round runs projected Newton with
/// lambda1, lambda2 fixed, then: eta = 1 - sqrt(|1 - t|); when eta < 0 the garment and t
/// go back to the start and lambda1 doubles; then lambda1 doubles again while eta < 0.99
/// and lambda1 < 1e6, else lambda2 += lambda1 (1 - t). The loop ends when snapping t to
/// 1 (avatar A(t) → A, garment still) is collision free by CCD; t is then set to 1. It
/// also ends, kStalled, after parameters.max_stalled_rounds rounds in a row in which t
/// gained less than 1% of its remaining distance to 1: raising lambda1 cannot move a
/// pinched garment. A round that resets does not count.
/// With a guide, the rounds start where follow_guide led along its path, with its
/// multipliers; a reset still goes back to the initial garment at t = 0.
/// `interrupter` sees every Newton step of the rounds (ProjectedNewton::minimize) and is
/// checked after each round, before `on_round`.
/// @pre the initial garment and A0 are intersection free (the shrink step's invariant).
/// @throw std::invalid_argument, InputError as GarmentProblem's constructor.
/// @throw Interrupted from `interrupter`.
InflationResult inflate_avatar(const GarmentScene& scene, const RetargetParameters& parameters,
                               const InflationCallback& on_round = {},
                               Interrupter& interrupter = null_interrupter(),
                               const InflationGuide& guide = {});

}  // namespace gr
