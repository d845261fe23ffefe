#pragma once

#include <cstdio>
#include <string>

#include <fmt/format.h>

#include "core/common/stopwatch.hpp"

namespace gr {

/// Progress lines on stderr: "[   1.234 s] stage: message". Silent when quiet.
class Progress {
 public:
  explicit Progress(bool quiet) : quiet_(quiet) {}

  /// Seconds since construction.
  double elapsed_seconds() const { return stopwatch_.seconds(); }

  template <typename... Args>
  void log(const char* stage, fmt::format_string<Args...> format, Args&&... args) const {
    if (quiet_) return;
    std::fprintf(stderr, "[%9.3f s] %-8s %s\n", elapsed_seconds(), stage,
                 fmt::format(format, std::forward<Args>(args)...).c_str());
    std::fflush(stderr);
  }

  bool quiet() const { return quiet_; }

 private:
  bool quiet_;
  Stopwatch stopwatch_;
};

/// Wall time of one stage, for the report.
using StageTimer = Stopwatch;

}  // namespace gr
