#pragma once

#include "core/energies/distance_field.hpp"
#include "shrink/level_set/signed_distance_grid.hpp"

namespace gr {

/// The avatar's signed distance between voxels: a tricubic B-spline whose control points
/// are the grid's voxel values (C2: value, gradient and Hessian continuous; reproduces
/// linear fields exactly, smooths curved ones by O(voxel²·curvature)). Outside the box of
/// stored voxels (grown by three voxels, where the spline is flat at the background value)
/// it continues smoothly as background + sqrt(r² + h²) − h, r the distance to that box and
/// h the voxel size, so values keep growing away from the avatar with a continuous
/// gradient. Between the narrow band and that box the value is the background and the
/// gradient zero; so it is inside, beyond the band of a narrow-band grid (at -background).
/// Thread-safe: every call reads the shared grid through its own accessor.
class GridDistanceField final : public DistanceField {
 public:
  /// Keeps a (shared) copy of `grid`. @throw std::logic_error when the grid is empty.
  explicit GridDistanceField(const SignedDistanceGrid& grid);

  /// Value at p (normalized scene units), gradient and Hessian when requested.
  double evaluate(const Vector3d& p, Vector3d* gradient = nullptr,
                  Eigen::Matrix3d* hessian = nullptr) const override;

  const SignedDistanceGrid& grid() const { return grid_; }

 private:
  SignedDistanceGrid grid_;
  Vector3d box_min_;  ///< index space box where the spline is used
  Vector3d box_max_;
};

}  // namespace gr
