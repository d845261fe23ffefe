#include <cstdio>

#include "app/cli/commands.hpp"
#include "retarget/outcome.hpp"
#include "retarget/run/run_control.hpp"

namespace gr {

void add_limit_options(CLI::App& command, RunLimits& limits) {
  command
      .add_option("--max-input-mb", limits.max_input_mb,
                  "Largest input file read, in MB (each file is checked to be a regular file "
                  "of at most this size before it is opened)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command
      .add_option("--max-faces", limits.max_faces,
                  "Refuse a garment or avatar of more faces than this, before any work (0: no "
                  "limit)")
      ->check(CLI::NonNegativeNumber);
  command
      .add_option("--max-memory-mb", limits.max_memory_mb,
                  "Refuse a scene whose estimated peak memory is above this before the solve, "
                  "and stop a run that grows beyond it (exit 9) (0: no limit)")
      ->check(CLI::NonNegativeNumber);
  command
      .add_option("--timeout", limits.timeout_seconds,
                  "Stop the run after this many seconds of wall time (exit 9, nothing written) "
                  "(0: none)")
      ->check(CLI::NonNegativeNumber);
}

int report_stopped_run(const Interrupted& stopped) {
  std::fprintf(stderr, "garment-retarget: error: %s; nothing was written\n", stopped.what());
  return stopped.reason() == InterruptReason::kCancelled ? to_exit_code(Outcome::kInterrupted)
                                                         : to_exit_code(Outcome::kLimitReached);
}

}  // namespace gr
