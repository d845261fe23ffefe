#pragma once

#include <optional>
#include <stdexcept>
#include <string>

#include <Eigen/Core>

namespace gr {

/// Why long work stopped before its end.
enum class InterruptReason {
  kCancelled,    ///< asked to stop: Ctrl-C, SIGTERM, a caller's cancel
  kTimeout,      ///< a deadline passed
  kMemoryLimit,  ///< the process grew beyond its memory limit
};

/// Long work stopped by its Interrupter. It leaves no result of its own; the message names
/// the stage it stopped in.
class Interrupted : public std::runtime_error {
 public:
  Interrupted(InterruptReason reason, const std::string& message)
      : std::runtime_error(message), reason_(reason) {}
  InterruptReason reason() const { return reason_; }

 private:
  InterruptReason reason_;
};

/// One accepted step of an iterative solve (ProjectedNewton::minimize).
struct SolverStep {
  int iteration = 0;  ///< accepted steps so far
  double energy = 0.0;
  double step = 0.0;                       ///< fraction of the search direction taken
  double gradient_norm = 0.0;              ///< ||g||_2 at the point before the step
  double elapsed_seconds = 0.0;            ///< since the solve started
  double damping = 0.0;                    ///< the solver's regularization for the next step
  const Eigen::VectorXd* point = nullptr;  ///< the accepted point, valid during the call
};

/// What long work (a level set, a binding, a solve) tells the outside while it runs, and
/// how the outside stops it, as OpenVDB's util::NullInterrupter: the work names its
/// stages, reports how far it is, and calls check() where it can stop cleanly. Called
/// from the thread that started the work, never from worker threads; an implementation
/// need not be thread safe.
class Interrupter {
 public:
  virtual ~Interrupter() = default;

  /// A stage of the work starts; later progress and an Interrupted name it.
  virtual void start(const std::string& /*stage*/) {}
  /// How much of the current stage is done, in [0, 1].
  virtual void progress(double /*fraction*/) {}
  /// An iterative solve accepted a step.
  virtual void step(const SolverStep& /*step*/) {}
  /// Why the work must stop now, naming the current stage; nullopt to go on.
  virtual std::optional<Interrupted> interruption() const { return std::nullopt; }

  /// @throw Interrupted when interruption() says to stop.
  void check() const {
    if (std::optional<Interrupted> stop = interruption()) throw *stop;
  }
  bool was_interrupted() const { return interruption().has_value(); }
  /// progress(fraction), then check(): a point where the work reports and may stop.
  void checkpoint(double fraction) {
    progress(fraction);
    check();
  }
};

/// Reports nowhere and never stops: the default of every long operation.
class NullInterrupter final : public Interrupter {};

/// A shared NullInterrupter (it holds no state, so any thread may use it).
inline Interrupter& null_interrupter() {
  static NullInterrupter none;
  return none;
}

/// `interrupter`, or the null interrupter when there is none.
inline Interrupter& or_null(Interrupter* interrupter) {
  return interrupter ? *interrupter : null_interrupter();
}

/// Passes everything on to another interrupter: the base of adaptors that change one thing.
class ForwardingInterrupter : public Interrupter {
 public:
  explicit ForwardingInterrupter(Interrupter& next) : next_(next) {}

  void start(const std::string& stage) override { next_.start(stage); }
  void progress(double fraction) override { next_.progress(fraction); }
  void step(const SolverStep& step) override { next_.step(step); }
  std::optional<Interrupted> interruption() const override { return next_.interruption(); }

 protected:
  Interrupter& next() const { return next_; }

 private:
  Interrupter& next_;
};

}  // namespace gr
