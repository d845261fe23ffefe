#pragma once

#include <optional>
#include <stdexcept>
#include <string>

#include "core/common/stopwatch.hpp"
#include "shrink/common/progress.hpp"

namespace gr {

/// What a run may take of the machine; checked before reading (file types and sizes),
/// before the solve (faces, estimated memory) and in every long loop (time, memory).
struct RunLimits {
  double max_input_mb = 1024.0;  ///< each input file, checked before it is opened
  int max_faces = 0;             ///< garment and avatar each, after triangulation; 0: none
  double max_memory_mb = 0.0;    ///< resident memory, estimated before the solve; 0: none
  double timeout_seconds = 0.0;  ///< wall time of the whole run; 0: none
};

/// Why a run stopped before its end.
enum class StopReason {
  kTimeout,      ///< the run's deadline (--timeout) passed
  kInterrupted,  ///< Ctrl-C, SIGTERM, or request_stop() from a caller
  kMemoryLimit,  ///< the process grew beyond the run's memory limit (--max-memory-mb)
};

/// A run stopped by its limits or at a user's request: it leaves no result of its own.
class RunStopped : public std::runtime_error {
 public:
  RunStopped(StopReason reason, const std::string& message)
      : std::runtime_error(message), reason_(reason) {}
  StopReason reason() const { return reason_; }

 private:
  StopReason reason_;
};

/// Asks every running RunControl of this process to stop at its next check. Only sets an
/// atomic flag, so a signal handler may call it.
void request_stop() noexcept;
/// Forgets an earlier request_stop() (the next run of a long-lived process starts clean).
void clear_stop_request() noexcept;

/// Installs handlers for SIGINT and SIGTERM that call request_stop(); a second signal of the
/// same kind ends the process as it would have without the handler.
void stop_on_signals();

/// The limits of one run, checked by its long loops: a deadline, the process's memory, and
/// the process-wide stop request.
class RunControl {
 public:
  /// @param timeout_seconds wall time allowed from now; unset or non-positive: none.
  /// @param max_memory_mb resident memory allowed to the process; unset or non-positive: none.
  explicit RunControl(std::optional<double> timeout_seconds = {},
                      std::optional<double> max_memory_mb = {});

  /// @throw RunStopped naming `stage` when the deadline passed, the memory limit is
  ///        exceeded or a stop was requested.
  void check(const std::string& stage) const;
  /// What check() would throw, without throwing: for hooks that may not throw (a stage's
  /// progress callback asks to cancel instead).
  std::optional<RunStopped> poll(const std::string& stage) const;

  /// Seconds left before the deadline; infinity without one.
  double seconds_left() const;

 private:
  std::optional<double> timeout_seconds_;
  std::optional<double> max_memory_mb_;
  Stopwatch clock_;
};

/// Runs `work(hook)`, where `hook` is a ProgressCallback that asks the stage to cancel
/// when `control` must stop; the stage's OperationCancelled comes back as the RunStopped
/// that caused it.
template <typename Work>
decltype(auto) with_stop_hook(const RunControl& control, Work&& work) {
  std::optional<RunStopped> stop;
  const ProgressCallback hook = [&control, &stop](const std::string& stage, double) {
    stop = control.poll(stage);
    return !stop;
  };
  try {
    return work(hook);
  } catch (const OperationCancelled&) {
    if (stop) throw RunStopped(*stop);
    throw;
  }
}

/// Peak resident memory a retarget is expected to take, in MB, from its face counts: a
/// linear fit to measured runs (bench/results/memory_estimate.md), which the peaks
/// measured stay below.
double estimated_peak_memory_mb(int garment_faces, int avatar_faces);

/// Resident memory of this process now, in MB (0 where /proc is not readable).
double resident_memory_mb();

}  // namespace gr
