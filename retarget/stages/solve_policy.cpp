#include "retarget/stages/solve_policy.hpp"

namespace gr {

SolveStep SolvePolicy::next(const InflationAttempt& attempt,
                            const std::function<int()>& pressed_pairs) {
  const bool first = attempts_++ == 0;
  if (attempt.succeeded) return SolveStep::kFit;
  if (!attempt.stalled) return SolveStep::kGiveUp;
  if (first && pressed_pairs && pressed_pairs() > 0) {
    widened_ = true;
    return SolveStep::kWiderBarrier;
  }
  // The thinner avatar is tried in the barrier the garment first stalled in, then in the
  // wider one, whichever came first.
  if (skeleton_shrink_ && !thinner_tried_) {
    thinner_tried_ = true;
    widened_ = false;
    return SolveStep::kThinnerShrink;
  }
  if (!widened_) {
    widened_ = true;
    return SolveStep::kWiderBarrier;
  }
  return SolveStep::kGiveUp;
}

}  // namespace gr
