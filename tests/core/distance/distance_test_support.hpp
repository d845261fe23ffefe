#pragma once

#include <array>
#include <limits>
#include <random>

#include <Eigen/Geometry>

#include <catch2/catch.hpp>

#include "core/common/types.hpp"
#include "core/finite_difference.hpp"

namespace gr::test {

/// A seeded random rotation, so every closest-feature case is checked off the axes too.
inline Eigen::Matrix3d random_rotation(unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  Eigen::Quaterniond q(normal(rng), normal(rng), normal(rng), normal(rng));
  return q.normalized().toRotationMatrix();
}

/// Stencil positions stacked vertex-major into one vector, and back.
template <std::size_t N>
Eigen::VectorXd stack(const std::array<Vector3d, N>& x) {
  Eigen::VectorXd out(3 * N);
  for (std::size_t i = 0; i < N; ++i) out.segment<3>(3 * static_cast<Eigen::Index>(i)) = x[i];
  return out;
}

template <std::size_t N>
std::array<Vector3d, N> unstack(const Eigen::VectorXd& v) {
  std::array<Vector3d, N> out;
  for (std::size_t i = 0; i < N; ++i) out[i] = v.segment<3>(3 * static_cast<Eigen::Index>(i));
  return out;
}

/// Applies a rotation and an offset to every stencil point.
template <std::size_t N>
std::array<Vector3d, N> moved(std::array<Vector3d, N> x, const Eigen::Matrix3d& R,
                              const Vector3d& offset) {
  for (Vector3d& p : x) p = R * p + offset;
  return x;
}

/// Smallest squared distance between two sampled point sets given as functions of grid
/// parameters in [0, 1]² (a segment ignores its second parameter): an upper bound on the
/// true squared distance, within the sampling spacing of it.
template <typename SurfaceA, typename SurfaceB>
double sampled_distance_sq(const SurfaceA& a, int a_dims, const SurfaceB& b, int b_dims,
                           int samples) {
  double best = std::numeric_limits<double>::infinity();
  const auto grid = [samples](int dims, auto&& visit) {
    for (int i = 0; i <= samples; ++i)
      for (int j = 0; j <= (dims == 2 ? samples - i : 0); ++j)
        visit(double(i) / samples, double(j) / samples);
  };
  grid(a_dims, [&](double s, double t) {
    const Vector3d pa = a(s, t);
    grid(b_dims, [&](double u, double v) { best = std::min(best, (pa - b(u, v)).squaredNorm()); });
  });
  return best;
}

/// Checks a stencil function's gradient and Hessian against central differences at x.
/// The absolute allowance (1e-10 for O(1) coordinates) covers the h² truncation where the
/// value and its gradient vanish (a point on the feature).
template <typename Value, typename Gradient, typename Hessian>
void check_derivatives(const Value& value, const Gradient& gradient, const Hessian& hessian,
                       const Eigen::VectorXd& x) {
  const Eigen::VectorXd g = gradient(x);
  const Eigen::MatrixXd H = hessian(x);
  const Eigen::VectorXd g_fd = fd_gradient(value, x);
  const Eigen::MatrixXd H_fd = fd_hessian(gradient, x);
  CAPTURE(x.transpose(), g.transpose(), g_fd.transpose());
  CHECK(fd_matches(g, g_fd, 1e-6, 1e-4));
  CHECK(fd_matches(H, H_fd, 1e-6, 1e-4));
  CHECK((H - H.transpose()).norm() <= 1e-12 * std::max(1.0, H.norm()));
}

}  // namespace gr::test
