#pragma once

#include <sys/resource.h>

#include <fstream>
#include <string>

namespace gr::bench {

/// CPU time of this process so far (user and system), seconds.
inline double cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

/// Resets the process's resident high-water mark, so that the next peak is the next run's.
inline void reset_peak_memory() { std::ofstream("/proc/self/clear_refs") << "5"; }

/// The process's resident high-water mark since the last reset, MiB (VmHWM).
inline double peak_memory_since_reset_mb() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
  return 0.0;
}

}  // namespace gr::bench
