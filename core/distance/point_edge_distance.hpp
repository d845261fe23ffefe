#pragma once

#include "core/distance/distance_stencil.hpp"
#include "core/distance/distance_type.hpp"

namespace gr {

// Squared distance from point p to segment [e0, e1] (squared scene units), with
// derivatives with respect to (p, e0, e1). With a type, the distance of that
// closest-feature case (smooth, even where it is not the closest one); without, the true
// distance (classified with point_edge_distance_type). Derivatives are those of the
// case's formula. @pre for P_E: e0 ≠ e1.

/// The closest-feature case as a form on the stencil (p, e0, e1).
DistanceStencil point_edge_stencil(PointEdgeDistanceType type);

double point_edge_distance_sq(const Vector3d& p, const Vector3d& e0, const Vector3d& e1);
double point_edge_distance_sq(const Vector3d& p, const Vector3d& e0, const Vector3d& e1,
                              PointEdgeDistanceType type);
Vector9d point_edge_distance_sq_gradient(const Vector3d& p, const Vector3d& e0, const Vector3d& e1,
                                         PointEdgeDistanceType type);
Matrix9d point_edge_distance_sq_hessian(const Vector3d& p, const Vector3d& e0, const Vector3d& e1,
                                        PointEdgeDistanceType type);

}  // namespace gr
