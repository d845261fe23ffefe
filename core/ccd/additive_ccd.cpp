#include "core/ccd/additive_ccd.hpp"

#include <algorithm>
#include <cmath>

#include "core/distance/edge_edge_distance.hpp"
#include "core/distance/point_triangle_distance.hpp"

namespace gr {
namespace {

/// Fraction of the remaining gap each advance may consume (< 1 leaves room for rounding).
constexpr double kAdvanceFraction = 0.9;
/// Stop once the gap above the separation is below this fraction of the starting gap:
/// the step is then within a hair of the time the pair reaches the separation.
constexpr double kStopGapFraction = 0.01;

struct PointTriangle {
  static DistanceStencil stencil(const std::array<Vector3d, 4>& x) {
    return point_triangle_stencil(point_triangle_distance_type(x[0], x[1], x[2], x[3]));
  }
  /// Bound on how fast the distance can shrink: the point's speed plus the fastest corner.
  static double relative_speed(const std::array<Vector3d, 4>& p) {
    return p[0].norm() + std::max({p[1].norm(), p[2].norm(), p[3].norm()});
  }
};

struct EdgeEdge {
  static DistanceStencil stencil(const std::array<Vector3d, 4>& x) {
    return edge_edge_stencil(edge_edge_distance_type(x[0], x[1], x[2], x[3]));
  }
  static double relative_speed(const std::array<Vector3d, 4>& p) {
    return std::max(p[0].norm(), p[1].norm()) + std::max(p[2].norm(), p[3].norm());
  }
};

std::array<Vector3d, 4> lerp(const std::array<Vector3d, 4>& x0, const std::array<Vector3d, 4>& x1,
                             double t) {
  std::array<Vector3d, 4> x;
  for (int i = 0; i < 4; ++i) x[i] = x0[i] + t * (x1[i] - x0[i]);
  return x;
}

template <typename Pair>
double additive_ccd(const std::array<Vector3d, 4>& x0, const std::array<Vector3d, 4>& x1,
                    const CcdOptions& options, double t_max) {
  // Distances are translation invariant: only motion relative to the mean matters.
  std::array<Vector3d, 4> p;
  Vector3d mean = Vector3d::Zero();
  for (int i = 0; i < 4; ++i) {
    p[i] = x1[i] - x0[i];
    mean += 0.25 * p[i];
  }
  for (Vector3d& pi : p) pi -= mean;
  const double speed = Pair::relative_speed(p);
  if (speed == 0.0) return t_max;

  const DistanceStencil start_stencil = Pair::stencil(x0);
  Vector12d grad;
  const double d0 = std::sqrt(stencil_distance_sq<4>(start_stencil, x0, &grad));
  if (d0 == 0.0) return 0.0;
  double g = std::max(options.min_separation_ratio * d0, options.min_separation);
  if (d0 <= g) {
    double rate = 0.0;  // d(d²)/dt at t = 0
    for (int i = 0; i < 4; ++i) rate += grad.segment<3>(3 * i).dot(x1[i] - x0[i]);
    if (rate < 0.0) return 0.0;
    g = options.min_separation_ratio * d0;
  }

  double t = 0.0, d = d0;
  for (int iteration = 0; iteration < options.max_iterations; ++iteration) {
    const double advance = kAdvanceFraction * (d - g) / speed;
    if (t + advance >= t_max) return t_max;
    t += advance;
    const std::array<Vector3d, 4> x = lerp(x0, x1, t);
    d = std::sqrt(stencil_distance_sq<4>(Pair::stencil(x), x));
    if (d - g <= kStopGapFraction * (d0 - g)) break;
  }
  return t;
}

}  // namespace

double point_triangle_ccd(const std::array<Vector3d, 4>& x0, const std::array<Vector3d, 4>& x1,
                          const CcdOptions& options, double t_max) {
  return additive_ccd<PointTriangle>(x0, x1, options, t_max);
}

double edge_edge_ccd(const std::array<Vector3d, 4>& x0, const std::array<Vector3d, 4>& x1,
                     const CcdOptions& options, double t_max) {
  return additive_ccd<EdgeEdge>(x0, x1, options, t_max);
}

}  // namespace gr
