#include "core/distance/distance_type.hpp"

#include <array>
#include <limits>

#include "core/distance/distance_forms.hpp"

namespace gr {
namespace {

/// Squared distance from p to the segment with the type already classified.
double point_segment_distance_sq(const Vector3d& p, const Vector3d& e0, const Vector3d& e1,
                                 PointEdgeDistanceType type) {
  switch (type) {
    case PointEdgeDistanceType::P_E0: return (p - e0).squaredNorm();
    case PointEdgeDistanceType::P_E1: return (p - e1).squaredNorm();
    default: return point_line_form(p - e0, e1 - e0);
  }
}

/// True when u and v are (nearly) parallel, or one of them is zero.
bool nearly_parallel(const Vector3d& u, const Vector3d& v) {
  return u.cross(v).squaredNorm() <= kParallelSinSq * u.squaredNorm() * v.squaredNorm();
}

}  // namespace

PointEdgeDistanceType point_edge_distance_type(const Vector3d& p, const Vector3d& e0,
                                               const Vector3d& e1) {
  const Vector3d u = e1 - e0;
  const double s = (p - e0).dot(u);
  if (s <= 0.0) return PointEdgeDistanceType::P_E0;
  if (s >= u.squaredNorm()) return PointEdgeDistanceType::P_E1;
  return PointEdgeDistanceType::P_E;
}

PointTriangleDistanceType point_triangle_distance_type(const Vector3d& p, const Vector3d& t0,
                                                       const Vector3d& t1, const Vector3d& t2) {
  const Vector3d e1 = t1 - t0, e2 = t2 - t0, a = p - t0;
  if (!nearly_parallel(e1, e2)) {
    // Barycentric coordinates of p's projection on the plane (Cramer's rule on the 2×2
    // normal equations).
    const double e11 = e1.squaredNorm(), e12 = e1.dot(e2), e22 = e2.squaredNorm();
    const double r1 = a.dot(e1), r2 = a.dot(e2);
    const double det = e11 * e22 - e12 * e12;
    const double b1 = (r1 * e22 - r2 * e12) / det;
    const double b2 = (r2 * e11 - r1 * e12) / det;
    if (b1 >= 0.0 && b2 >= 0.0 && b1 + b2 <= 1.0) return PointTriangleDistanceType::P_T;
  }
  // Outside the triangle (or degenerate): the closest point lies on one of its sides.
  const std::array<const Vector3d*, 3> corner{&t0, &t1, &t2};
  PointTriangleDistanceType best = PointTriangleDistanceType::P_T0;
  double best_distance = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    const Vector3d& s0 = *corner[k];
    const Vector3d& s1 = *corner[(k + 1) % 3];
    const PointEdgeDistanceType side = point_edge_distance_type(p, s0, s1);
    const double distance = point_segment_distance_sq(p, s0, s1, side);
    if (distance < best_distance) {
      best_distance = distance;
      if (side == PointEdgeDistanceType::P_E0)
        best = static_cast<PointTriangleDistanceType>(k);
      else if (side == PointEdgeDistanceType::P_E1)
        best = static_cast<PointTriangleDistanceType>((k + 1) % 3);
      else
        best = static_cast<PointTriangleDistanceType>(3 + k);
    }
  }
  return best;
}

EdgeEdgeDistanceType edge_edge_distance_type(const Vector3d& ea0, const Vector3d& ea1,
                                             const Vector3d& eb0, const Vector3d& eb1) {
  const Vector3d u = ea1 - ea0, v = eb1 - eb0, w = ea0 - eb0;
  if (!nearly_parallel(u, v)) {
    // Parameters of the lines' closest points ea0 + s u and eb0 + t v.
    const double uu = u.squaredNorm(), uv = u.dot(v), vv = v.squaredNorm();
    const double uw = u.dot(w), vw = v.dot(w);
    const double det = uu * vv - uv * uv;
    const double s = (uv * vw - vv * uw) / det;
    const double t = (uu * vw - uv * uw) / det;
    if (s > 0.0 && s < 1.0 && t > 0.0 && t < 1.0) return EdgeEdgeDistanceType::EA_EB;
  }
  // The constrained minimum lies on the boundary of the parameter square: one endpoint
  // against the other segment.
  struct Option {
    double distance;
    EdgeEdgeDistanceType type;
  };
  const auto endpoint_vs = [](const Vector3d& p, const Vector3d& s0, const Vector3d& s1,
                              EdgeEdgeDistanceType at0, EdgeEdgeDistanceType at1,
                              EdgeEdgeDistanceType interior) {
    const PointEdgeDistanceType side = point_edge_distance_type(p, s0, s1);
    const double distance = point_segment_distance_sq(p, s0, s1, side);
    const EdgeEdgeDistanceType type = side == PointEdgeDistanceType::P_E0   ? at0
                                      : side == PointEdgeDistanceType::P_E1 ? at1
                                                                            : interior;
    return Option{distance, type};
  };
  using T = EdgeEdgeDistanceType;
  const std::array<Option, 4> options{
      endpoint_vs(ea0, eb0, eb1, T::EA0_EB0, T::EA0_EB1, T::EA0_EB),
      endpoint_vs(ea1, eb0, eb1, T::EA1_EB0, T::EA1_EB1, T::EA1_EB),
      endpoint_vs(eb0, ea0, ea1, T::EA0_EB0, T::EA1_EB0, T::EA_EB0),
      endpoint_vs(eb1, ea0, ea1, T::EA0_EB1, T::EA1_EB1, T::EA_EB1)};
  Option best = options[0];
  for (const Option& option : options)
    if (option.distance < best.distance) best = option;
  return best.type;
}

}  // namespace gr
