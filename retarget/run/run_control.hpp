#pragma once

#include <optional>
#include <string>

#include "core/common/interrupter.hpp"
#include "core/common/stopwatch.hpp"

namespace gr {

/// What a run may take of the machine; checked before reading (file types and sizes),
/// before the solve (faces, estimated memory) and in every long loop (time, memory).
struct RunLimits {
  double max_input_mb = 1024.0;  ///< each input file, checked before it is opened
  int max_faces = 0;             ///< garment and avatar each, after triangulation; 0: none
  double max_memory_mb = 0.0;    ///< resident memory, estimated before the solve; 0: none
  double timeout_seconds = 0.0;  ///< wall time of the whole run; 0: none
};

/// Asks every running RunControl of this process to stop at its next check. Only sets an
/// atomic flag, so a signal handler may call it.
void request_stop() noexcept;
/// Forgets an earlier request_stop() (the next run of a long-lived process starts clean).
void clear_stop_request() noexcept;

/// Installs handlers for SIGINT and SIGTERM that call request_stop(); a second signal of the
/// same kind ends the process as it would have without the handler.
void stop_on_signals();

/// The limits of one run, as the interrupter its long loops check: a deadline, the
/// process's memory, and the process-wide stop request. A stop is an Interrupted naming
/// the stage last started: kCancelled for a stop request, kTimeout, kMemoryLimit.
class RunControl final : public Interrupter {
 public:
  /// @param timeout_seconds wall time allowed from now; unset or non-positive: none.
  /// @param max_memory_mb resident memory allowed to the process; unset or non-positive: none.
  explicit RunControl(std::optional<double> timeout_seconds = {},
                      std::optional<double> max_memory_mb = {});

  void start(const std::string& stage) override { stage_ = stage; }
  std::optional<Interrupted> interruption() const override;

  /// Seconds left before the deadline; infinity without one.
  double seconds_left() const;

 private:
  std::optional<double> timeout_seconds_;
  std::optional<double> max_memory_mb_;
  Stopwatch clock_;
  std::string stage_ = "the run";
};

/// Peak resident memory a retarget is expected to take, in MB, from its face counts: a
/// linear fit to measured runs (bench/results/memory_estimate.md), which the peaks
/// measured stay below.
double estimated_peak_memory_mb(int garment_faces, int avatar_faces);

/// Resident memory of this process now, in MB (0 where /proc is not readable).
double resident_memory_mb();

}  // namespace gr
