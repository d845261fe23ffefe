#include "core/distance/point_edge_distance.hpp"

namespace gr {

DistanceStencil point_edge_stencil(PointEdgeDistanceType type) {
  // Stencil order: p = 0, e0 = 1, e1 = 2.
  switch (type) {
    case PointEdgeDistanceType::P_E0: return {DistanceForm::PointPoint, {{{0, 1}, {0, 0}, {0, 0}}}};
    case PointEdgeDistanceType::P_E1: return {DistanceForm::PointPoint, {{{0, 2}, {0, 0}, {0, 0}}}};
    case PointEdgeDistanceType::P_E:
    default: return {DistanceForm::PointLine, {{{0, 1}, {2, 1}, {0, 0}}}};
  }
}

double point_edge_distance_sq(const Vector3d& p, const Vector3d& e0, const Vector3d& e1) {
  return point_edge_distance_sq(p, e0, e1, point_edge_distance_type(p, e0, e1));
}

double point_edge_distance_sq(const Vector3d& p, const Vector3d& e0, const Vector3d& e1,
                              PointEdgeDistanceType type) {
  return stencil_distance_sq<3>(point_edge_stencil(type), {p, e0, e1});
}

Vector9d point_edge_distance_sq_gradient(const Vector3d& p, const Vector3d& e0, const Vector3d& e1,
                                         PointEdgeDistanceType type) {
  return stencil_distance_sq_gradient<3>(point_edge_stencil(type), {p, e0, e1});
}

Matrix9d point_edge_distance_sq_hessian(const Vector3d& p, const Vector3d& e0, const Vector3d& e1,
                                        PointEdgeDistanceType type) {
  return stencil_distance_sq_hessian<3>(point_edge_stencil(type), {p, e0, e1});
}

}  // namespace gr
