#include "core/distance/point_triangle_distance.hpp"

namespace gr {

DistanceStencil point_triangle_stencil(PointTriangleDistanceType type) {
  // Stencil order: p = 0, t0 = 1, t1 = 2, t2 = 3; edge k runs from t_k to t_(k+1).
  using T = PointTriangleDistanceType;
  switch (type) {
    case T::P_T0: return {DistanceForm::PointPoint, {{{0, 1}, {0, 0}, {0, 0}}}};
    case T::P_T1: return {DistanceForm::PointPoint, {{{0, 2}, {0, 0}, {0, 0}}}};
    case T::P_T2: return {DistanceForm::PointPoint, {{{0, 3}, {0, 0}, {0, 0}}}};
    case T::P_E0: return {DistanceForm::PointLine, {{{0, 1}, {2, 1}, {0, 0}}}};
    case T::P_E1: return {DistanceForm::PointLine, {{{0, 2}, {3, 2}, {0, 0}}}};
    case T::P_E2: return {DistanceForm::PointLine, {{{0, 3}, {1, 3}, {0, 0}}}};
    case T::P_T:
    default: return {DistanceForm::PointPlane, {{{0, 1}, {2, 1}, {3, 1}}}};
  }
}

double point_triangle_distance_sq(const Vector3d& p, const Vector3d& t0, const Vector3d& t1,
                                  const Vector3d& t2) {
  return point_triangle_distance_sq(p, t0, t1, t2, point_triangle_distance_type(p, t0, t1, t2));
}

double point_triangle_distance_sq(const Vector3d& p, const Vector3d& t0, const Vector3d& t1,
                                  const Vector3d& t2, PointTriangleDistanceType type) {
  return stencil_distance_sq<4>(point_triangle_stencil(type), {p, t0, t1, t2});
}

Vector12d point_triangle_distance_sq_gradient(const Vector3d& p, const Vector3d& t0,
                                              const Vector3d& t1, const Vector3d& t2,
                                              PointTriangleDistanceType type) {
  return stencil_distance_sq_gradient<4>(point_triangle_stencil(type), {p, t0, t1, t2});
}

Matrix12d point_triangle_distance_sq_hessian(const Vector3d& p, const Vector3d& t0,
                                             const Vector3d& t1, const Vector3d& t2,
                                             PointTriangleDistanceType type) {
  return stencil_distance_sq_hessian<4>(point_triangle_stencil(type), {p, t0, t1, t2});
}

}  // namespace gr
