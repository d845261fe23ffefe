#pragma once

#include "core/common/types.hpp"
#include "core/distance/stencil.hpp"

namespace gr {

// IPC's mollifier for nearly parallel edges (Li et al. 2020, section 4.3): the edge–edge
// barrier is multiplied by m(|ea × eb|²), which falls smoothly to zero as the edges become
// parallel, where the closest-feature case switches and the distance is not smooth.

/// The threshold eps_x = 1e-3 |ea|² |eb|² on rest positions (scene units to the fourth).
double edge_edge_mollifier_threshold(const Vector3d& ea0_rest, const Vector3d& ea1_rest,
                                     const Vector3d& eb0_rest, const Vector3d& eb1_rest);

/// m(x) = (2 - x/eps) x/eps for x < eps, 1 beyond (C1 at eps). @pre eps > 0.
double mollifier(double x, double eps);
double mollifier_first_derivative(double x, double eps);
double mollifier_second_derivative(double x, double eps);

/// m(|(ea1 - ea0) × (eb1 - eb0)|², eps) with gradient and Hessian with respect to
/// (ea0, ea1, eb0, eb1) when the pointers are non-null. @pre eps > 0.
double edge_edge_mollifier(const Vector3d& ea0, const Vector3d& ea1, const Vector3d& eb0,
                           const Vector3d& eb1, double eps, Vector12d* gradient = nullptr,
                           Matrix12d* hessian = nullptr);

}  // namespace gr
