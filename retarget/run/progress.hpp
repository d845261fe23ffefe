#pragma once

#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "core/common/stopwatch.hpp"
#include "retarget/run/run_control.hpp"

namespace gr {

/// What a stage reports while it runs: progress lines on stderr ("[   1.234 s] stage:
/// message", silent when quiet), the warnings it raises for the report, and the run's
/// limits. It is the interrupter the stages hand to their long work: it passes stages,
/// progress and the stop on to the run's control, and logs the Newton steps of the solves
/// it is given, the first ones then every tenth, under the stage last started.
class Progress final : public Interrupter {
 public:
  /// @param control the run's limits (a RunControl); null: none but a stop request
  ///        (Ctrl-C). It must outlive the Progress.
  explicit Progress(bool quiet, Interrupter* control = nullptr)
      : quiet_(quiet), control_(control ? control : &unlimited_) {}
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void start(const std::string& stage) override {
    stage_ = stage;
    control_->start(stage);
  }
  void progress(double fraction) override { control_->progress(fraction); }
  void step(const SolverStep& step) override {
    control_->step(step);
    if (step.iteration <= kNewtonLogFirst || step.iteration % kNewtonLogEvery == 0)
      log(stage_.c_str(), "  Newton {:4d}  E {:.9g}  step {:.3g}  |g| {:.3g}  mu {:.2g}",
          step.iteration, step.energy, step.step, step.gradient_norm, step.damping);
  }
  std::optional<Interrupted> interruption() const override { return control_->interruption(); }

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

  bool quiet() const { return quiet_; }

 private:
  /// Newton lines: the first steps, then every tenth.
  static constexpr int kNewtonLogFirst = 3;
  static constexpr int kNewtonLogEvery = 10;

  bool quiet_;
  RunControl unlimited_;
  Interrupter* control_;
  std::string stage_;
  std::vector<std::string> warnings_;
  Stopwatch stopwatch_;
};

/// Wall time of one stage, for the report.
using StageTimer = Stopwatch;

}  // namespace gr
