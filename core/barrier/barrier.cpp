#include "core/barrier/barrier.hpp"

#include <cmath>
#include <limits>

namespace gr {

double barrier(double x, double xhat) {
  if (x >= xhat) return 0.0;
  if (x <= 0.0) return std::numeric_limits<double>::infinity();
  const double gap = x - xhat;
  return -gap * gap * std::log(x / xhat);
}

double barrier_first_derivative(double x, double xhat) {
  if (x >= xhat) return 0.0;
  if (x <= 0.0) return -std::numeric_limits<double>::infinity();
  const double gap = x - xhat;
  return -2.0 * gap * std::log(x / xhat) - gap * gap / x;
}

double barrier_second_derivative(double x, double xhat) {
  if (x >= xhat) return 0.0;
  if (x <= 0.0) return std::numeric_limits<double>::infinity();
  const double ratio = (x - xhat) / x;
  return -2.0 * std::log(x / xhat) - 4.0 * ratio + ratio * ratio;
}

}  // namespace gr
