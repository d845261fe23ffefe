#pragma once

namespace gr {

// IPC's clamped log barrier on squared distances (Li et al. 2020):
//   b(x) = -(x - xhat)² ln(x / xhat) for 0 < x < xhat, and 0 for x >= xhat,
// with x a squared distance and xhat = dhat² (dhat in normalized scene units). Value,
// slope and curvature all vanish at xhat, so b is C2 there; b grows without bound as x → 0.

/// b(x); +inf for x <= 0. @pre xhat > 0.
double barrier(double x, double xhat);
/// db/dx; 0 for x >= xhat, -inf for x <= 0. @pre xhat > 0.
double barrier_first_derivative(double x, double xhat);
/// d²b/dx²; 0 for x >= xhat, +inf for x <= 0. @pre xhat > 0.
double barrier_second_derivative(double x, double xhat);

}  // namespace gr
