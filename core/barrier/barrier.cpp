#include "core/barrier/barrier.hpp"

#include <limits>

#include <sleef.h>

namespace gr {
namespace {

/// The natural logarithm, the same to the bit on every x86-64 CPU: glibc's log has an FMA
/// variant, chosen at run time, that differs by an ulp on some arguments, and the barrier's
/// rounding carries into the garment (bench/results/parameter_choices.md). SLEEF's
/// portable C build, within 1.0 ulp.
double portable_log(double x) { return Sleef_cinz_logd1_u10purec(x); }

}  // namespace

double barrier(double x, double xhat) {
  if (x >= xhat) return 0.0;
  if (x <= 0.0) return std::numeric_limits<double>::infinity();
  const double gap = x - xhat;
  return -gap * gap * portable_log(x / xhat);
}

double barrier_first_derivative(double x, double xhat) {
  if (x >= xhat) return 0.0;
  if (x <= 0.0) return -std::numeric_limits<double>::infinity();
  const double gap = x - xhat;
  return -2.0 * gap * portable_log(x / xhat) - gap * gap / x;
}

double barrier_second_derivative(double x, double xhat) {
  if (x >= xhat) return 0.0;
  if (x <= 0.0) return std::numeric_limits<double>::infinity();
  const double ratio = (x - xhat) / x;
  return -2.0 * portable_log(x / xhat) - 4.0 * ratio + ratio * ratio;
}

}  // namespace gr
