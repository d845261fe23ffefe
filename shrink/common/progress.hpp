#pragma once

#include <functional>
#include <stdexcept>
#include <string>

namespace gr {

/// Progress of a long operation: the stage's name and how much of it is done, in [0, 1].
/// Return false to cancel; the operation then throws OperationCancelled. Called from the
/// thread that started the operation, never from worker threads.
using ProgressCallback = std::function<bool(const std::string& stage, double fraction)>;

/// A long operation stopped because its progress callback returned false.
class OperationCancelled : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Calls `progress` when there is one and throws OperationCancelled when it asks to stop.
inline void report_progress(const ProgressCallback& progress, const std::string& stage,
                            double fraction) {
  if (progress && !progress(stage, fraction)) throw OperationCancelled("cancelled during " + stage);
}

}  // namespace gr
