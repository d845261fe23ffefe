#include <catch2/catch.hpp>

#include <vector>

#include "retarget/stages/solve_policy.hpp"

using gr::InflationAttempt;
using gr::SolvePolicy;
using gr::SolveStep;

namespace {

constexpr InflationAttempt kStalled{false, true};
constexpr InflationAttempt kSucceeded{true, false};
constexpr InflationAttempt kSolverFailed{false, false};

/// The steps the policy takes while every inflation stalls, with the barrier factor each
/// retry inflates with, and how often it asked for the pressed pairs.
struct Walk {
  std::vector<SolveStep> steps;
  std::vector<double> factors;
  int pressed_asked = 0;
};

Walk walk_while_stalled(bool skeleton_shrink, int pressed_pairs) {
  SolvePolicy policy(skeleton_shrink);
  Walk walk;
  const auto pressed = [&] {
    ++walk.pressed_asked;
    return pressed_pairs;
  };
  for (int attempt = 0; attempt < 10; ++attempt) {
    const SolveStep step = policy.next(kStalled, pressed);
    walk.steps.push_back(step);
    if (step == SolveStep::kGiveUp) break;
    walk.factors.push_back(policy.barrier_factor());
  }
  return walk;
}

}  // namespace

TEST_CASE("solve policy: a succeeded inflation fits, a failed solver gives up", "[solve_policy]") {
  SolvePolicy first(true);
  CHECK(first.next(kSucceeded, [] { return 3; }) == SolveStep::kFit);
  SolvePolicy failed(true);
  int asked = 0;
  CHECK(failed.next(kSolverFailed, [&] { return ++asked; }) == SolveStep::kGiveUp);
  CHECK(asked == 0);
}

TEST_CASE("solve policy: a skeleton shrink stalled at crossings widens, thins, widens again",
          "[solve_policy]") {
  const Walk walk = walk_while_stalled(true, 4);
  CHECK(walk.steps == std::vector<SolveStep>{SolveStep::kWiderBarrier, SolveStep::kThinnerShrink,
                                             SolveStep::kWiderBarrier, SolveStep::kGiveUp});
  // The thinner avatar inflates in the barrier the garment first stalled in.
  CHECK(walk.factors == std::vector<double>{2.0, 1.0, 2.0});
  CHECK(walk.pressed_asked == 1);
}

TEST_CASE("solve policy: a skeleton shrink stalled elsewhere thins first, then widens",
          "[solve_policy]") {
  const Walk walk = walk_while_stalled(true, 0);
  CHECK(walk.steps == std::vector<SolveStep>{SolveStep::kThinnerShrink, SolveStep::kWiderBarrier,
                                             SolveStep::kGiveUp});
  CHECK(walk.factors == std::vector<double>{1.0, 2.0});
}

TEST_CASE("solve policy: a level-set shrink only widens, once", "[solve_policy]") {
  for (const int pressed : {0, 5}) {
    const Walk walk = walk_while_stalled(false, pressed);
    CHECK(walk.steps == std::vector<SolveStep>{SolveStep::kWiderBarrier, SolveStep::kGiveUp});
    CHECK(walk.factors == std::vector<double>{2.0});
  }
}

TEST_CASE("solve policy: a retry that succeeds fits, whatever came before", "[solve_policy]") {
  SolvePolicy policy(true);
  CHECK(policy.next(kStalled, [] { return 0; }) == SolveStep::kThinnerShrink);
  CHECK(policy.next(kSucceeded, [] { return 0; }) == SolveStep::kFit);
  SolvePolicy after_widening(false);
  CHECK(after_widening.next(kStalled, [] { return 1; }) == SolveStep::kWiderBarrier);
  CHECK(after_widening.next(kSolverFailed, [] { return 1; }) == SolveStep::kGiveUp);
}
