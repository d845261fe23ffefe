#include "shrink/level_set/grid_distance_field.hpp"

#include <cmath>

#include "shrink/level_set/signed_distance_grid_impl.hpp"

namespace gr {

namespace {

/// Beyond the stored voxels the spline needs two voxels of support to become flat; one
/// more keeps the flat region non-empty.
constexpr double kFlatMarginVoxels = 3.0;

/// Uniform cubic B-spline basis at t in [0, 1) with first and second derivatives.
struct Basis {
  double w[4], dw[4], ddw[4];
  explicit Basis(double t) {
    const double s = 1.0 - t, t2 = t * t, t3 = t2 * t;
    w[0] = s * s * s / 6.0;
    w[1] = (3.0 * t3 - 6.0 * t2 + 4.0) / 6.0;
    w[2] = (-3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0) / 6.0;
    w[3] = t3 / 6.0;
    dw[0] = -0.5 * s * s;
    dw[1] = 1.5 * t2 - 2.0 * t;
    dw[2] = -1.5 * t2 + t + 0.5;
    dw[3] = 0.5 * t2;
    ddw[0] = s;
    ddw[1] = 3.0 * t - 2.0;
    ddw[2] = 1.0 - 3.0 * t;
    ddw[3] = t;
  }
};

}  // namespace

GridDistanceField::GridDistanceField(const SignedDistanceGrid& grid) : grid_(grid) {
  const openvdb::CoordBBox& box = grid_.impl().active_index_box;
  box_min_ = Vector3d(box.min().x(), box.min().y(), box.min().z()).array() - kFlatMarginVoxels;
  box_max_ = Vector3d(box.max().x(), box.max().y(), box.max().z()).array() + kFlatMarginVoxels;
}

double GridDistanceField::evaluate(const Vector3d& p, Vector3d* gradient,
                                   Eigen::Matrix3d* hessian) const {
  const SignedDistanceGrid::Impl& impl = grid_.impl();
  const double h = impl.voxel_size;
  const Vector3d u = p / h;
  const Vector3d q = u.cwiseMax(box_min_).cwiseMin(box_max_);

  Eigen::Vector3i base;
  Basis basis[3] = {Basis(0), Basis(0), Basis(0)};
  for (int a = 0; a < 3; ++a) {
    const double f = std::floor(q[a]);
    base[a] = static_cast<int>(f) - 1;
    basis[a] = Basis(q[a] - f);
  }
  auto accessor = impl.grid->getConstUnsafeAccessor();
  double value = 0.0;
  Vector3d g = Vector3d::Zero();
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  const bool want_hessian = hessian != nullptr;
  const Basis &bx = basis[0], &by = basis[1], &bz = basis[2];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      // Reduce along z first: value, d/dz and d²/dz² of the (i, j) column.
      double c = 0.0, cz = 0.0, czz = 0.0;
      for (int k = 0; k < 4; ++k) {
        const double v = accessor.getValue(openvdb::Coord(base[0] + i, base[1] + j, base[2] + k));
        c += bz.w[k] * v;
        cz += bz.dw[k] * v;
        czz += bz.ddw[k] * v;
      }
      const double wxy = bx.w[i] * by.w[j];
      value += wxy * c;
      g[0] += bx.dw[i] * by.w[j] * c;
      g[1] += bx.w[i] * by.dw[j] * c;
      g[2] += wxy * cz;
      if (want_hessian) {
        H(0, 0) += bx.ddw[i] * by.w[j] * c;
        H(1, 1) += bx.w[i] * by.ddw[j] * c;
        H(2, 2) += wxy * czz;
        H(0, 1) += bx.dw[i] * by.dw[j] * c;
        H(0, 2) += bx.dw[i] * by.w[j] * cz;
        H(1, 2) += bx.w[i] * by.dw[j] * cz;
      }
    }
  g /= h;
  H /= h * h;

  // Along clamped axes the spline stays at its face value (and is flat there); the
  // smoothed distance to the box takes over.
  const Vector3d offset = (u - q) * h;
  const double stretched = std::sqrt(offset.squaredNorm() + h * h);
  value += stretched - h;
  if (gradient) {
    for (int a = 0; a < 3; ++a)
      if (u[a] != q[a]) g[a] = 0.0;
    *gradient = g + offset / stretched;
  }
  if (hessian) {
    H(1, 0) = H(0, 1);
    H(2, 0) = H(0, 2);
    H(2, 1) = H(1, 2);
    Eigen::Matrix3d outside = -offset * offset.transpose() / (stretched * stretched * stretched);
    for (int a = 0; a < 3; ++a) {
      if (u[a] == q[a]) continue;
      H.row(a).setZero();
      H.col(a).setZero();
      outside(a, a) += 1.0 / stretched;
    }
    *hessian = H + outside;
  }
  return value;
}

}  // namespace gr
