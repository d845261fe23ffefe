#pragma once

namespace gr {

/// Exit codes of `garment-retarget`, documented in docs/exit-codes.md.
enum ExitCode : int {
  kExitSuccess = 0,        ///< done; for retarget and validate: certified intersection-free
  kExitIntersections = 1,  ///< validate found intersections; retarget's output failed certification
  kExitBadInput = 2,       ///< bad command line or input file
  kExitNoValidShrink = 3,  ///< no shrunk avatar free of the garment could be found
  kExitSolverFailure = 4,  ///< the solver did not converge or met a non-finite energy
  kExitOutputError = 5,    ///< an output file or folder could not be written
  kExitInternalError = 6,  ///< a bug: please report it with the inputs
  /// certified and written, but the garment's shape changed beyond the shape thresholds
  /// (retarget), or the garment's shape differs from --source beyond them (validate)
  kExitShapeChanged = 7,
  kExitBatchJobsFailed = 8,  ///< batch: some jobs did not end certified (see its summary.csv)
  /// the run reached --timeout, or grew beyond --max-memory-mb while running; it wrote nothing
  kExitLimitReached = 9,
  kExitInterrupted = 10,  ///< Ctrl-C or SIGTERM; the run wrote nothing
};

}  // namespace gr
