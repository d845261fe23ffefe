#pragma once

#include "core/common/types.hpp"

namespace gr {

/// Closest features of a point and a segment [e0, e1].
enum class PointEdgeDistanceType {
  P_E0,  ///< endpoint e0
  P_E1,  ///< endpoint e1
  P_E,   ///< interior of the segment
};

/// Closest features of a point and a triangle (t0, t1, t2). Edge k runs from t_k to t_(k+1).
enum class PointTriangleDistanceType {
  P_T0,
  P_T1,
  P_T2,
  P_E0,  ///< interior of edge t0 t1
  P_E1,  ///< interior of edge t1 t2
  P_E2,  ///< interior of edge t2 t0
  P_T,   ///< interior of the triangle
};

/// Closest features of segments a = [ea0, ea1] and b = [eb0, eb1].
enum class EdgeEdgeDistanceType {
  EA0_EB0,
  EA0_EB1,
  EA1_EB0,
  EA1_EB1,
  EA_EB0,  ///< eb0 against the interior of a
  EA_EB1,  ///< eb1 against the interior of a
  EA0_EB,  ///< ea0 against the interior of b
  EA1_EB,  ///< ea1 against the interior of b
  EA_EB,   ///< interiors of both (the lines' distance)
};

/// Below this sin² of the angle between two edges (or two triangle sides) they count as
/// parallel (a degenerate triangle): the interior case is ill-conditioned there and a
/// boundary feature attains the same distance to within |edge| · 1e-9 (1e-9 rad and up
/// keep the interior case; tests sweep 1e-10 rad as parallel).
constexpr double kParallelSinSq = 1e-18;

/// Which features of the segment are closest to p. A zero-length segment gives P_E0.
PointEdgeDistanceType point_edge_distance_type(const Vector3d& p, const Vector3d& e0,
                                               const Vector3d& e1);

/// Which features of the triangle are closest to p. A degenerate (zero or near-zero area)
/// triangle is treated as its three sides, so P_T is never returned for it.
PointTriangleDistanceType point_triangle_distance_type(const Vector3d& p, const Vector3d& t0,
                                                       const Vector3d& t1, const Vector3d& t2);

/// Which features of two segments are closest. For parallel (or nearly parallel, see
/// kParallelSinSq) or zero-length segments a point–edge or point–point case is returned,
/// never EA_EB.
EdgeEdgeDistanceType edge_edge_distance_type(const Vector3d& ea0, const Vector3d& ea1,
                                             const Vector3d& eb0, const Vector3d& eb1);

}  // namespace gr
