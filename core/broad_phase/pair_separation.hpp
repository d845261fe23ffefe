#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/common/types.hpp"

namespace gr {

namespace pair_separation_detail {

/// Gap along axis n between the projections of groups [0, split) and [split, 4) of the
/// positions in `frames` (one or two 4-vertex arrays), over |n|; 0 when they overlap or n
/// is zero.
template <std::size_t Frames>
double axis_gap(const std::array<const std::array<Vector3d, 4>*, Frames>& frames, int split,
                const Vector3d& n) {
  const double length_sq = n.squaredNorm();
  if (!(length_sq > 0.0)) return 0.0;
  constexpr double inf = std::numeric_limits<double>::infinity();
  double min_a = inf, max_a = -inf, min_b = inf, max_b = -inf;
  for (const auto* x : frames)
    for (int i = 0; i < 4; ++i) {
      const double s = n.dot((*x)[i]);
      if (i < split) {
        min_a = std::min(min_a, s);
        max_a = std::max(max_a, s);
      } else {
        min_b = std::min(min_b, s);
        max_b = std::max(max_b, s);
      }
    }
  return std::max({min_b - max_a, min_a - max_b, 0.0}) / std::sqrt(length_sq);
}

template <std::size_t Frames>
double lower_bound(const std::array<const std::array<Vector3d, 4>*, Frames>& frames, int split,
                   double enough) {
  const std::array<Vector3d, 4>& x = *frames[0];
  // Boxes of the two groups over every frame: their Euclidean gap.
  Vector3d lo_a = x[0], hi_a = x[0], lo_b = x[split], hi_b = x[split];
  Vector3d centroid_a = Vector3d::Zero(), centroid_b = Vector3d::Zero();
  for (const auto* frame : frames)
    for (int i = 0; i < 4; ++i) {
      const Vector3d& p = (*frame)[i];
      if (i < split) {
        lo_a = lo_a.cwiseMin(p);
        hi_a = hi_a.cwiseMax(p);
        centroid_a += p;
      } else {
        lo_b = lo_b.cwiseMin(p);
        hi_b = hi_b.cwiseMax(p);
        centroid_b += p;
      }
    }
  double bound = (lo_a - hi_b).cwiseMax(lo_b - hi_a).cwiseMax(0.0).norm();
  if (bound >= enough) return bound;
  const auto try_axis = [&](const Vector3d& n) {
    bound = std::max(bound, axis_gap(frames, split, n));
    return bound >= enough;
  };
  const Vector3d d = centroid_b / static_cast<double>(Frames * (4 - split)) -
                     centroid_a / static_cast<double>(Frames * split);
  if (split == 1) {
    // A point and a triangle: the triangle's normal (layers), then the in-plane normals of
    // its edges (a point beside the triangle, as neighbours in one mesh are).
    const Vector3d n = (x[2] - x[1]).cross(x[3] - x[1]);
    if (try_axis(n)) return bound;
    for (int k = 0; k < 3; ++k)
      if (try_axis(n.cross(x[1 + (k + 1) % 3] - x[1 + k]))) return bound;
    return bound;
  }
  // Two edges: their common normal (crossing layers), then the centroid offset with each
  // edge's direction removed (edges side by side).
  const Vector3d ea = x[1] - x[0], eb = x[3] - x[2];
  if (try_axis(ea.cross(eb))) return bound;
  for (const Vector3d* e : {&ea, &eb}) {
    const double e_sq = e->squaredNorm();
    if (e_sq > 0.0 && try_axis(d - (d.dot(*e) / e_sq) * *e)) return bound;
  }
  return bound;
}

}  // namespace pair_separation_detail

/// A lower bound on the distance between the two primitives of a contact pair, cheap
/// enough to run on every candidate before the narrow phase. The pair's four vertices are
/// split into A = hull(x[0, split)) and B = hull(x[split, 4)): split 1 for a point and a
/// triangle, 2 for two edges.
///
/// Over a linear motion x0 → x1 each vertex stays on its segment, so every primitive at
/// every time in [0, 1] lies in the hull of its vertices' start and end positions. Any
/// fixed axis n on which those hulls project to disjoint intervals bounds the distance at
/// every time by the gap between the intervals (over |n|). The bound is the largest of:
/// the Euclidean gap between the hulls' axis-aligned boxes, and the gaps along axes taken
/// from the start positions: for a point and a triangle, the triangle's normal and the
/// in-plane normals of its edges; for two edges, their common normal and the offset between
/// their centroids with either edge's direction removed. The boxes miss neighbours in one
/// mesh (whose boxes overlap) and tilted layers; these axes do not. Degenerate axes (zero
/// length) are skipped; 0 when nothing separates the hulls. With motion, the bound is also
/// taken relative to the pair's mean motion (a common translation changes no distance), and
/// the larger is returned. Units: those of the positions.
/// @param enough stop as soon as the bound reaches this (the caller only compares with it).
/// @pre split is 1 or 2.
inline double pair_separation_lower_bound(const std::array<Vector3d, 4>& x0,
                                          const std::array<Vector3d, 4>& x1, int split,
                                          double enough = std::numeric_limits<double>::infinity()) {
  const double bound = pair_separation_detail::lower_bound<2>({&x0, &x1}, split, enough);
  if (bound >= enough) return bound;
  // The same bound in a frame that follows the pair's mean motion: distances do not change
  // under a common translation, and positions relative to a linearly moving point still
  // move linearly. Two primitives carried along together stay tight there.
  Vector3d m0 = Vector3d::Zero(), m1 = Vector3d::Zero();
  for (int i = 0; i < 4; ++i) {
    m0 += x0[i];
    m1 += x1[i];
  }
  m0 *= 0.25;
  m1 *= 0.25;
  std::array<Vector3d, 4> r0, r1;
  for (int i = 0; i < 4; ++i) {
    r0[i] = x0[i] - m0;
    r1[i] = x1[i] - m1;
  }
  return std::max(bound, pair_separation_detail::lower_bound<2>({&r0, &r1}, split, enough));
}

/// The bound above for positions x, without motion.
inline double pair_separation_lower_bound(const std::array<Vector3d, 4>& x, int split,
                                          double enough = std::numeric_limits<double>::infinity()) {
  return pair_separation_detail::lower_bound<1>({&x}, split, enough);
}

/// Whether the pair on rows `ids` of the stacked positions (split as above) may come within
/// `threshold` somewhere along the motion V0 → V1: its separation bound is below the
/// threshold. When V0 and V1 share their storage, the bound at V0 without motion (cheaper).
/// @param V0 #V×3 and @param V1 #V×3 positions. @pre every id is a row of both.
inline bool pair_may_come_within(const Eigen::Ref<const MatrixX3d>& V0,
                                 const Eigen::Ref<const MatrixX3d>& V1,
                                 const std::array<int, 4>& ids, int split, double threshold) {
  const auto gather = [&ids](const Eigen::Ref<const MatrixX3d>& V) {
    return std::array<Vector3d, 4>{V.row(ids[0]).transpose(), V.row(ids[1]).transpose(),
                                   V.row(ids[2]).transpose(), V.row(ids[3]).transpose()};
  };
  const std::array<Vector3d, 4> x0 = gather(V0);
  const double bound = V0.data() == V1.data()
                           ? pair_separation_lower_bound(x0, split, threshold)
                           : pair_separation_lower_bound(x0, gather(V1), split, threshold);
  return bound < threshold;
}

}  // namespace gr
