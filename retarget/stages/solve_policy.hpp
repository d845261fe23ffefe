#pragma once

#include <functional>

namespace gr {

/// What the solve does after an inflation attempt.
enum class SolveStep {
  kFit,            ///< the inflation succeeded: fit the garment
  kWiderBarrier,   ///< inflate again with a barrier kStalledBarrierFactor times wider
  kThinnerShrink,  ///< shrink the avatar thinner (kStalledPullbackFactor of the pullback) and
                   ///< inflate again in the first barrier
  kGiveUp,         ///< end the run with the inflation's failure
};

/// How an inflation attempt ended, as the policy sees it.
struct InflationAttempt {
  bool succeeded = false;
  /// Failed short of its goal with a working solver (the solver itself did not fail): a
  /// retry may get further.
  bool stalled = false;
};

/// The stall and retry policy of the inflation. Layers and pieces pressed together by the
/// growing avatar (a trouser cuff inside a shoe) can jam in a barrier thinner than their gap
/// to each other; a crossing the input came with cannot slide at all: both want a wider
/// barrier first. Else a skeleton-shrunk avatar is shrunk thinner, which leaves the garment
/// more room between body parts, and a wider barrier comes last.
class SolvePolicy {
 public:
  /// When the inflation fails from a skeleton-shrunk avatar, it runs again from one shrunk
  /// with this fraction of its pullback.
  static constexpr double kStalledPullbackFactor = 0.2;
  /// A stalled inflation runs once more with a barrier this many times wider.
  static constexpr double kStalledBarrierFactor = 2.0;
  /// A stalled inflation whose tangle pairs lie closer than this fraction of dhat is jammed
  /// at a crossing the input came with: the barrier there is overpowered.
  static constexpr double kPressedGap = 0.01;

  /// @param skeleton_shrink whether the avatar was shrunk onto its skeleton (a thinner shrink
  ///        exists to try).
  explicit SolvePolicy(bool skeleton_shrink) : skeleton_shrink_(skeleton_shrink) {}

  /// The step after `attempt`. `pressed_pairs` counts the garment's pairs pressed together at
  /// crossings the input came with; it is asked only after the first attempt stalled.
  SolveStep next(const InflationAttempt& attempt, const std::function<int()>& pressed_pairs);

  /// The factor on the first barrier width (dhat) that the next inflation runs with.
  double barrier_factor() const { return widened_ ? kStalledBarrierFactor : 1.0; }

 private:
  bool skeleton_shrink_;
  int attempts_ = 0;
  bool widened_ = false;
  bool thinner_tried_ = false;
};

}  // namespace gr
