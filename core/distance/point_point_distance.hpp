#pragma once

#include "core/common/types.hpp"
#include "core/distance/stencil.hpp"

namespace gr {

/// |p - q|², in squared scene units.
double point_point_distance_sq(const Vector3d& p, const Vector3d& q);
/// Gradient of point_point_distance_sq with respect to (p, q).
Vector6d point_point_distance_sq_gradient(const Vector3d& p, const Vector3d& q);
/// Hessian of point_point_distance_sq with respect to (p, q); constant.
Matrix6d point_point_distance_sq_hessian(const Vector3d& p, const Vector3d& q);

}  // namespace gr
