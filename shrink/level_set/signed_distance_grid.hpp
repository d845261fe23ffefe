#pragma once

#include <cstddef>
#include <memory>

#include <Eigen/Geometry>

#include "core/common/interrupter.hpp"
#include "core/common/types.hpp"

namespace gr {

/// How to build an avatar's signed distance grid.
struct SignedDistanceOptions {
  /// How far outside the avatar distances are stored, in normalized scene units (at
  /// least 3 voxels are used). Beyond it the grid holds this value; the sampler adds the
  /// distance to the grid's box far away. The fit term pulls garment points only within it.
  double exterior_band = 0.1;
  /// Told the stages and their progress, and asked between parts of the build whether to
  /// stop; null: none.
  Interrupter* interrupter = nullptr;
  /// Store the distance at every voxel inside (the level-set shrink walks to the medial
  /// region). When false the grid keeps only the band (exterior_band on both sides of the
  /// surface, at least 3 voxels) and holds -background deeper inside, which is all the fit
  /// term reads (it pulls garment points near the surface) and is faster to build.
  bool full_depth = true;
};

/// An avatar's signed distance (positive outside) on a sparse OpenVDB grid. In a narrow
/// band around the surface voxels hold OpenVDB's distances (to a triangle found through the
/// voxel's neighbours: exact almost everywhere, in rare concave places larger than the
/// nearest by up to a voxel or two); deeper inside, exact distances at every voxel (full
/// depth) or -background (narrow band). The sign comes from the generalized winding number
/// (inside where its magnitude exceeds 1/2), so open, overlapping or inverted parts get a
/// sign that does not leak. Voxel centres sit at integer multiples of the voxel size. Cheap
/// to copy (copies share the immutable grid); safe to read from many threads.
class SignedDistanceGrid {
 public:
  class Impl;

  SignedDistanceGrid();
  explicit SignedDistanceGrid(std::shared_ptr<const Impl> impl);

  /// Edge of a voxel, in normalized scene units.
  double voxel_size() const;
  /// The value stored everywhere outside the exterior band (normalized scene units).
  double background() const;
  /// The most negative stored value: minus the deepest interior depth (full depth), or
  /// minus about the band's width (narrow band).
  double min_value() const;
  /// Whether every voxel inside holds its distance (SignedDistanceOptions::full_depth).
  bool full_depth() const;
  /// Voxels that hold a distance.
  std::size_t active_voxel_count() const;
  /// Bytes held by the grid's tree.
  std::size_t memory_bytes() const;
  /// Smallest box holding every voxel centre that holds a distance (normalized units).
  Eigen::AlignedBox3d active_box() const;
  /// The stored value of voxel (i, j, k) (centre at voxel_size · (i, j, k)), no
  /// interpolation: the background outside the band.
  double voxel_value(const Eigen::Vector3i& ijk) const;

  const Impl& impl() const;

 private:
  std::shared_ptr<const Impl> impl_;
};

/// Builds the signed distance of `avatar` (#V×3 positions, #F×3 faces, in normalized scene
/// units). Faces need a consistent orientation per part (outward or all inward); parts may
/// be open, overlap or intersect. Zero-area faces are ignored for the sign.
/// Runs in parallel (TBB). Reports stages "unsigned distance", "sign", "interior" (the
/// last with full depth only).
/// @throw std::invalid_argument when voxel_size is not positive and finite, or the avatar
///        has no face or an index out of range.
/// @throw Interrupted from options.interrupter.
SignedDistanceGrid build_signed_distance(const TriangleMesh& avatar, double voxel_size,
                                         const SignedDistanceOptions& options = {});

}  // namespace gr
