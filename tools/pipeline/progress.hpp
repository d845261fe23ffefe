#pragma once

#include <chrono>
#include <cstdio>
#include <string>

#include <fmt/format.h>

namespace gr {

/// Progress lines on stderr: "[   1.234 s] stage: message". Silent when quiet.
class Progress {
 public:
  explicit Progress(bool quiet) : quiet_(quiet), start_(std::chrono::steady_clock::now()) {}

  double elapsed_seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

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
  std::chrono::steady_clock::time_point start_;
};

/// Wall time of one stage, for the report.
class StageTimer {
 public:
  StageTimer() : start_(std::chrono::steady_clock::now()) {}
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_;
};

}  // namespace gr
