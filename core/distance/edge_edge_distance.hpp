#pragma once

#include "core/distance/distance_stencil.hpp"
#include "core/distance/distance_type.hpp"

namespace gr {

// Squared distance between segments [ea0, ea1] and [eb0, eb1] (squared scene units), with
// derivatives with respect to (ea0, ea1, eb0, eb1). With a type, the distance of that
// closest-feature case; without, the true distance (edge_edge_distance_type, which never
// picks the ill-conditioned line–line case for nearly parallel edges). Derivatives are
// those of the case's formula. @pre for EA_EB: non-parallel edges; for a point–edge case:
// that edge has length > 0.

/// The closest-feature case as a form on the stencil (ea0, ea1, eb0, eb1).
DistanceStencil edge_edge_stencil(EdgeEdgeDistanceType type);

double edge_edge_distance_sq(const Vector3d& ea0, const Vector3d& ea1, const Vector3d& eb0,
                             const Vector3d& eb1);
double edge_edge_distance_sq(const Vector3d& ea0, const Vector3d& ea1, const Vector3d& eb0,
                             const Vector3d& eb1, EdgeEdgeDistanceType type);
Vector12d edge_edge_distance_sq_gradient(const Vector3d& ea0, const Vector3d& ea1,
                                         const Vector3d& eb0, const Vector3d& eb1,
                                         EdgeEdgeDistanceType type);
Matrix12d edge_edge_distance_sq_hessian(const Vector3d& ea0, const Vector3d& ea1,
                                        const Vector3d& eb0, const Vector3d& eb1,
                                        EdgeEdgeDistanceType type);

}  // namespace gr
