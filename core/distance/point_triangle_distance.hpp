#pragma once

#include "core/distance/distance_stencil.hpp"
#include "core/distance/distance_type.hpp"

namespace gr {

// Squared distance from point p to triangle (t0, t1, t2) (squared scene units), with
// derivatives with respect to (p, t0, t1, t2). With a type, the distance of that
// closest-feature case; without, the true distance (point_triangle_distance_type, which
// treats a degenerate triangle as its sides). Derivatives are those of the case's formula.
// @pre for P_T: a non-degenerate triangle; for an edge case: that edge has length > 0.

/// The closest-feature case as a form on the stencil (p, t0, t1, t2).
DistanceStencil point_triangle_stencil(PointTriangleDistanceType type);

double point_triangle_distance_sq(const Vector3d& p, const Vector3d& t0, const Vector3d& t1,
                                  const Vector3d& t2);
double point_triangle_distance_sq(const Vector3d& p, const Vector3d& t0, const Vector3d& t1,
                                  const Vector3d& t2, PointTriangleDistanceType type);
Vector12d point_triangle_distance_sq_gradient(const Vector3d& p, const Vector3d& t0,
                                              const Vector3d& t1, const Vector3d& t2,
                                              PointTriangleDistanceType type);
Matrix12d point_triangle_distance_sq_hessian(const Vector3d& p, const Vector3d& t0,
                                             const Vector3d& t1, const Vector3d& t2,
                                             PointTriangleDistanceType type);

}  // namespace gr
