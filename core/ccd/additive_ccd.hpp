#pragma once

#include <array>

#include "core/ccd/ccd.hpp"

namespace gr {

// Additive CCD for one pair (after Li et al. 2021, "Codimensional Incremental Potential
// Contact"): conservative advancement along the linear motion x0 → x1 using the pair's
// distance and a bound l_p on how fast it can shrink (the largest relative displacement
// after subtracting the mean motion). Each advance by gamma (d - g) / l_p keeps the
// distance above the separation g on the whole advanced interval, so every time it
// returns is safe; it stops when the remaining gap d - g is small against the starting gap,
// at t_max, or when the iteration budget is spent (returning the last safe time).
//
// The separation is g = max(ratio d0, min_separation) with d0 the starting distance. A pair
// that starts at or below min_separation returns 0 when its distance is decreasing at the
// start, and otherwise is held to ratio d0 only (so it can move apart). A pair at zero
// distance returns 0 unless it has no relative motion. Parallel, coplanar and degenerate
// configurations need no special case: the distance functions classify them.

/// Largest safe fraction in [0, t_max] for a point x[0] against the triangle x[1..3].
/// @param x0 positions at the start, x1 at the end of the motion (scene units).
double point_triangle_ccd(const std::array<Vector3d, 4>& x0, const std::array<Vector3d, 4>& x1,
                          const CcdOptions& options, double t_max = 1.0);

/// Largest safe fraction in [0, t_max] for edges (x[0], x[1]) and (x[2], x[3]).
double edge_edge_ccd(const std::array<Vector3d, 4>& x0, const std::array<Vector3d, 4>& x1,
                     const CcdOptions& options, double t_max = 1.0);

}  // namespace gr
