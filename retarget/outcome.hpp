#pragma once

#include <array>
#include <optional>

namespace gr {

/// How a command of garment-retarget ends. Each value is its exit code, so that the
/// command line, the batch's job records, the Python package and the docs read one table
/// (outcome_table) for codes and names.
enum class Outcome : int {
  kCertified = 0,      ///< done; for retarget and validate: certified intersection-free
  kNotCertified = 1,   ///< validate found intersections; retarget's output failed certification
  kBadInput = 2,       ///< bad command line or input file
  kNoValidShrink = 3,  ///< no shrunk avatar free of the garment could be found
  kSolverFailure = 4,  ///< the solver did not converge or met a non-finite energy
  kOutputError = 5,    ///< an output file or folder could not be written
  kInternalError = 6,  ///< a bug: please report it with the inputs
  /// certified and written, but the garment's shape changed beyond the shape thresholds
  /// (retarget), or the garment's shape differs from --source beyond them (validate)
  kShapeChanged = 7,
  kJobsFailed = 8,  ///< batch: some jobs did not end certified (see its summary.csv)
  /// the run reached --timeout, or grew beyond --max-memory-mb while running; it wrote nothing
  kLimitReached = 9,
  kInterrupted = 10,  ///< Ctrl-C or SIGTERM; the run wrote nothing
};

/// One outcome's exit code, the name reports and Python use for it, and its meaning.
struct OutcomeRow {
  Outcome outcome;
  int exit_code;
  const char* name;
  const char* meaning;
};

/// Every outcome, in exit-code order.
const std::array<OutcomeRow, 11>& outcome_table();

/// The process exit code of `outcome`.
constexpr int to_exit_code(Outcome outcome) { return static_cast<int>(outcome); }

/// The outcome's name ("certified", "not_certified", ...).
const char* to_string(Outcome outcome);

/// The outcome whose exit code is `code`; none for any other code.
std::optional<Outcome> outcome_for_exit_code(int code);

/// Whether a garment was written and certified free of intersections (kCertified, and
/// kShapeChanged, which writes and certifies but warns about the shape).
constexpr bool certified(Outcome outcome) {
  return outcome == Outcome::kCertified || outcome == Outcome::kShapeChanged;
}

}  // namespace gr
