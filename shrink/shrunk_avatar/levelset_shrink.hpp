#pragma once

#include "core/common/interrupter.hpp"
#include "core/common/types.hpp"
#include "shrink/level_set/signed_distance_grid.hpp"
#include "shrink/shrunk_avatar/shrink_result.hpp"

namespace gr {

/// How the level-set shrink searches for its erosion depth.
struct LevelsetShrinkOptions {
  /// Bisection stops when the feasible and infeasible depths are this close (normalized
  /// scene units); the returned depth is at most this much deeper than needed.
  double depth_tolerance = 1e-3;
  /// Step of the inward walk along the field, in voxels.
  double step_voxels = 0.5;
  /// Told stage "shrink" and the fraction of the bisection done, and asked at each step
  /// whether to stop; null: none.
  Interrupter* interrupter = nullptr;
};

/// The level-set shrunk avatar: every vertex walks inward down the avatar's signed distance
/// (against its gradient, through the tricubic sampler) to the eroded surface phi = -d, or
/// stops where phi stops decreasing (the medial region). A vertex already deeper than -d
/// (inner overlapping parts) stays. The depth d is the smallest found by bisection whose
/// shrunk avatar passes find_shrink_conflict against the garment; d = 0 (the avatar itself)
/// when the garment is already free of it.
/// @param avatar #V×3 / #F×3, normalized scene units; `grid` built from it. A narrow-band
///        grid serves erosions down to its band's depth, which is all most scenes need.
/// @param garment #G×3 / #H×3, same frame.
/// @throw ShrinkBandTooShallowError when the grid is narrow-band, walks reach its floor and
///        the deepest shrink there still conflicts: retry on a full-depth grid.
/// @throw NoValidShrinkError when even the deepest shrink (every vertex in the medial
///        region) conflicts with the garment; it names the conflict.
/// @throw std::invalid_argument on a non-positive tolerance or step.
/// @throw Interrupted from options.interrupter.
ShrinkResult shrink_levelset(const TriangleMesh& avatar, const TriangleMesh& garment,
                             const SignedDistanceGrid& grid,
                             const LevelsetShrinkOptions& options = {});

}  // namespace gr
