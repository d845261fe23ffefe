#include "core/distance/point_point_distance.hpp"

#include "core/distance/distance_stencil.hpp"

namespace gr {
namespace {

constexpr DistanceStencil kPointPoint{DistanceForm::PointPoint, {{{0, 1}, {0, 0}, {0, 0}}}};

}  // namespace

double point_point_distance_sq(const Vector3d& p, const Vector3d& q) {
  return (p - q).squaredNorm();
}

Vector6d point_point_distance_sq_gradient(const Vector3d& p, const Vector3d& q) {
  return stencil_distance_sq_gradient<2>(kPointPoint, {p, q});
}

Matrix6d point_point_distance_sq_hessian(const Vector3d& p, const Vector3d& q) {
  return stencil_distance_sq_hessian<2>(kPointPoint, {p, q});
}

}  // namespace gr
