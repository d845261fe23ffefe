#pragma once

#include "core/common/types.hpp"

namespace gr {

/// A signed distance to the avatar (positive outside), sampled through an interpolant
/// that is at least C1. Implemented outside the core (shrink/ with OpenVDB); the fit term
/// sees only this interface. Implementations are safe to call from many threads at once.
class DistanceField {
 public:
  virtual ~DistanceField() = default;
  /// Value at p, and gradient / Hessian when the pointers are not null. Same units and
  /// frame as the points (normalized scene units).
  virtual double evaluate(const Vector3d& p, Vector3d* gradient = nullptr,
                          Eigen::Matrix3d* hessian = nullptr) const = 0;
};

}  // namespace gr
