#include "core/distance/edge_edge_distance.hpp"

namespace gr {

DistanceStencil edge_edge_stencil(EdgeEdgeDistanceType type) {
  // Stencil order: ea0 = 0, ea1 = 1, eb0 = 2, eb1 = 3.
  using T = EdgeEdgeDistanceType;
  switch (type) {
    case T::EA0_EB0: return {DistanceForm::PointPoint, {{{0, 2}, {0, 0}, {0, 0}}}};
    case T::EA0_EB1: return {DistanceForm::PointPoint, {{{0, 3}, {0, 0}, {0, 0}}}};
    case T::EA1_EB0: return {DistanceForm::PointPoint, {{{1, 2}, {0, 0}, {0, 0}}}};
    case T::EA1_EB1: return {DistanceForm::PointPoint, {{{1, 3}, {0, 0}, {0, 0}}}};
    case T::EA_EB0: return {DistanceForm::PointLine, {{{2, 0}, {1, 0}, {0, 0}}}};
    case T::EA_EB1: return {DistanceForm::PointLine, {{{3, 0}, {1, 0}, {0, 0}}}};
    case T::EA0_EB: return {DistanceForm::PointLine, {{{0, 2}, {3, 2}, {0, 0}}}};
    case T::EA1_EB: return {DistanceForm::PointLine, {{{1, 2}, {3, 2}, {0, 0}}}};
    case T::EA_EB:
    default: return {DistanceForm::PointPlane, {{{2, 0}, {1, 0}, {3, 2}}}};
  }
}

double edge_edge_distance_sq(const Vector3d& ea0, const Vector3d& ea1, const Vector3d& eb0,
                             const Vector3d& eb1) {
  return edge_edge_distance_sq(ea0, ea1, eb0, eb1, edge_edge_distance_type(ea0, ea1, eb0, eb1));
}

double edge_edge_distance_sq(const Vector3d& ea0, const Vector3d& ea1, const Vector3d& eb0,
                             const Vector3d& eb1, EdgeEdgeDistanceType type) {
  return stencil_distance_sq<4>(edge_edge_stencil(type), {ea0, ea1, eb0, eb1});
}

Vector12d edge_edge_distance_sq_gradient(const Vector3d& ea0, const Vector3d& ea1,
                                         const Vector3d& eb0, const Vector3d& eb1,
                                         EdgeEdgeDistanceType type) {
  return stencil_distance_sq_gradient<4>(edge_edge_stencil(type), {ea0, ea1, eb0, eb1});
}

Matrix12d edge_edge_distance_sq_hessian(const Vector3d& ea0, const Vector3d& ea1,
                                        const Vector3d& eb0, const Vector3d& eb1,
                                        EdgeEdgeDistanceType type) {
  return stencil_distance_sq_hessian<4>(edge_edge_stencil(type), {ea0, ea1, eb0, eb1});
}

}  // namespace gr
