#include "retarget/outcome.hpp"

namespace gr {

namespace {

constexpr std::array<OutcomeRow, 11> kOutcomes{{
    {Outcome::kCertified, 0, "certified",
     "done; for retarget and validate: certified free of intersections"},
    {Outcome::kNotCertified, 1, "not_certified",
     "validate found intersections; retarget's written garment failed certification"},
    {Outcome::kBadInput, 2, "bad_input", "bad command line or input file"},
    {Outcome::kNoValidShrink, 3, "no_valid_shrink",
     "no shrunk avatar free of the garment could be found"},
    {Outcome::kSolverFailure, 4, "solver_failure",
     "the solver did not converge or met a non-finite energy"},
    {Outcome::kOutputError, 5, "output_error", "an output file or folder could not be written"},
    {Outcome::kInternalError, 6, "internal_error", "a bug: please report it with the inputs"},
    {Outcome::kShapeChanged, 7, "shape_changed",
     "certified and written, but the garment's shape changed beyond the shape thresholds"},
    {Outcome::kJobsFailed, 8, "jobs_failed",
     "batch: some jobs did not end certified (see its summary.csv)"},
    {Outcome::kLimitReached, 9, "limit_reached",
     "the run reached --timeout or --max-memory-mb; it wrote nothing"},
    {Outcome::kInterrupted, 10, "interrupted", "Ctrl-C or SIGTERM; the run wrote nothing"},
}};

constexpr bool rows_in_exit_code_order() {
  for (std::size_t i = 0; i < kOutcomes.size(); ++i)
    if (kOutcomes[i].exit_code != static_cast<int>(i) ||
        to_exit_code(kOutcomes[i].outcome) != static_cast<int>(i))
      return false;
  return true;
}
static_assert(rows_in_exit_code_order(), "outcome rows must follow their exit codes");

}  // namespace

const std::array<OutcomeRow, 11>& outcome_table() { return kOutcomes; }

const char* to_string(Outcome outcome) {
  return kOutcomes[static_cast<std::size_t>(to_exit_code(outcome))].name;
}

std::optional<Outcome> outcome_for_exit_code(int code) {
  if (code < 0 || code >= static_cast<int>(kOutcomes.size())) return std::nullopt;
  return kOutcomes[static_cast<std::size_t>(code)].outcome;
}

}  // namespace gr
