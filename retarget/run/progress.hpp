#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "core/common/stopwatch.hpp"
#include "retarget/run/run_control.hpp"

namespace gr {

/// What a stage reports while it runs: progress lines on stderr ("[   1.234 s] stage:
/// message", silent when quiet), the warnings it raises for the report, and the run's
/// limits, which its long loops check.
class Progress {
 public:
  /// @param control the run's limits; null: none but a stop request (Ctrl-C). It must
  ///        outlive the Progress.
  explicit Progress(bool quiet, const RunControl* control = nullptr)
      : quiet_(quiet), control_(control ? control : &unlimited()) {}

  /// Seconds since construction.
  double elapsed_seconds() const { return stopwatch_.seconds(); }

  template <typename... Args>
  void log(const char* stage, fmt::format_string<Args...> format, Args&&... args) const {
    if (quiet_) return;
    std::fprintf(stderr, "[%9.3f s] %-8s %s\n", elapsed_seconds(), stage,
                 fmt::format(format, std::forward<Args>(args)...).c_str());
    std::fflush(stderr);
  }

  /// A warning line, kept for the report.
  void warn(const std::string& warning) {
    log("warning", "{}", warning);
    warnings_.push_back(warning);
  }
  /// A warning for the report only (the stage logged it its own way).
  void record_warning(const std::string& warning) { warnings_.push_back(warning); }
  /// The warnings so far, in the order raised.
  const std::vector<std::string>& warnings() const { return warnings_; }

  const RunControl& control() const { return *control_; }
  bool quiet() const { return quiet_; }

 private:
  static const RunControl& unlimited() {
    static const RunControl control;
    return control;
  }

  bool quiet_;
  const RunControl* control_;
  std::vector<std::string> warnings_;
  Stopwatch stopwatch_;
};

/// Wall time of one stage, for the report.
using StageTimer = Stopwatch;

}  // namespace gr
