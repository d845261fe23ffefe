#include "retarget/run/run_control.hpp"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <limits>

#include <fmt/format.h>

namespace gr {

namespace {

std::atomic<bool> stop_requested{false};
static_assert(std::atomic<bool>::is_always_lock_free, "request_stop() runs in signal handlers");

extern "C" void stop_on_signal(int signal_number) {
  request_stop();
  // The next signal of this kind is not caught: a run that does not reach a check in time
  // can still be ended by the user.
  ::signal(signal_number, SIG_DFL);
}

}  // namespace

void request_stop() noexcept { stop_requested.store(true, std::memory_order_relaxed); }

void clear_stop_request() noexcept { stop_requested.store(false, std::memory_order_relaxed); }

void stop_on_signals() {
  struct sigaction action {};
  action.sa_handler = stop_on_signal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

RunControl::RunControl(std::optional<double> timeout_seconds, std::optional<double> max_memory_mb) {
  if (timeout_seconds && *timeout_seconds > 0.0) timeout_seconds_ = timeout_seconds;
  if (max_memory_mb && *max_memory_mb > 0.0) max_memory_mb_ = max_memory_mb;
}

double RunControl::seconds_left() const {
  if (!timeout_seconds_) return std::numeric_limits<double>::infinity();
  return *timeout_seconds_ - clock_.seconds();
}

std::optional<Interrupted> RunControl::interruption() const {
  if (stop_requested.load(std::memory_order_relaxed))
    return Interrupted(InterruptReason::kCancelled, "interrupted during " + stage_);
  if (timeout_seconds_ && clock_.seconds() > *timeout_seconds_)
    return Interrupted(InterruptReason::kTimeout,
                       fmt::format("timed out after {:.1f} s (--timeout {:g}) during {}",
                                   clock_.seconds(), *timeout_seconds_, stage_));
  if (max_memory_mb_) {
    const double resident = resident_memory_mb();
    if (resident > *max_memory_mb_)
      return Interrupted(InterruptReason::kMemoryLimit,
                         fmt::format("{:.0f} MB resident exceeds --max-memory-mb {:g} during {}",
                                     resident, *max_memory_mb_, stage_));
  }
  return std::nullopt;
}

double estimated_peak_memory_mb(int garment_faces, int avatar_faces) {
  constexpr double kBaseMb = 60.0;
  constexpr double kMbPerGarmentFace = 0.016;
  constexpr double kMbPerAvatarFace = 0.002;
  return kBaseMb + kMbPerGarmentFace * garment_faces + kMbPerAvatarFace * avatar_faces;
}

double resident_memory_mb() {
  std::FILE* statm = std::fopen("/proc/self/statm", "r");
  if (!statm) return 0.0;
  long total_pages = 0, resident_pages = 0;
  const int read = std::fscanf(statm, "%ld %ld", &total_pages, &resident_pages);
  std::fclose(statm);
  if (read != 2) return 0.0;
  return static_cast<double>(resident_pages) * static_cast<double>(sysconf(_SC_PAGESIZE)) /
         (1024.0 * 1024.0);
}

}  // namespace gr
