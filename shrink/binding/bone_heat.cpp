#include "shrink/binding/bone_heat.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/SparseCore>

#include "core/solver/linear_solver.hpp"

namespace gr {

namespace {

/// Least conductance of a mesh edge: keeps parts joined where both opposite angles are
/// right or obtuse (their clamped cotangents sum to 0).
constexpr double kMinEdgeWeight = 1e-3;
/// Distances within this relative amount of the nearest count as ties.
constexpr double kTieTolerance = 1e-9;

/// Symmetric cotangent edge weights (cot α + cot β) / 2, negative cotangents and those of
/// degenerate triangles counted as 0, then raised to kMinEdgeWeight. Adds each triangle's
/// third of its area to `area`.
Eigen::SparseMatrix<double> cotangent_weights(const TriangleMesh& avatar, Eigen::VectorXd& area) {
  const Eigen::Index n = avatar.vertices.rows();
  area = Eigen::VectorXd::Zero(n);
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<std::size_t>(avatar.faces.rows()) * 6);
  for (Eigen::Index f = 0; f < avatar.faces.rows(); ++f) {
    for (int c = 0; c < 3; ++c) {
      const int o = avatar.faces(f, c), a = avatar.faces(f, (c + 1) % 3),
                b = avatar.faces(f, (c + 2) % 3);
      const Vector3d u = (avatar.vertices.row(a) - avatar.vertices.row(o)).transpose();
      const Vector3d v = (avatar.vertices.row(b) - avatar.vertices.row(o)).transpose();
      const double twice_area = u.cross(v).norm();
      const bool degenerate = !(twice_area > 1e-12 * u.norm() * v.norm());
      const double half_cot = degenerate ? 0.0 : std::max(0.5 * u.dot(v) / twice_area, 0.0);
      triplets.emplace_back(a, b, half_cot);
      triplets.emplace_back(b, a, half_cot);
      area[o] += twice_area / 6.0;
    }
  }
  Eigen::SparseMatrix<double> weights(n, n);
  weights.setFromTriplets(triplets.begin(), triplets.end());
  for (Eigen::Index k = 0; k < weights.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(weights, k); it; ++it)
      it.valueRef() = std::max(it.value(), kMinEdgeWeight);
  return weights;
}

/// Per vertex, whether its connected part (along the edges of `weights`) has a vertex with
/// positive `heat`.
std::vector<char> heated_parts(const Eigen::SparseMatrix<double>& weights,
                               const Eigen::VectorXd& heat) {
  const Eigen::Index n = heat.size();
  std::vector<char> heated(static_cast<std::size_t>(n), 0);
  std::vector<Eigen::Index> queue;
  for (Eigen::Index v = 0; v < n; ++v)
    if (heat[v] > 0.0) {
      heated[static_cast<std::size_t>(v)] = 1;
      queue.push_back(v);
    }
  for (std::size_t head = 0; head < queue.size(); ++head)
    for (Eigen::SparseMatrix<double>::InnerIterator it(weights, queue[head]); it; ++it)
      if (!heated[static_cast<std::size_t>(it.index())]) {
        heated[static_cast<std::size_t>(it.index())] = 1;
        queue.push_back(it.index());
      }
  return heated;
}

}  // namespace

Eigen::MatrixXd bone_heat(const TriangleMesh& avatar, const std::vector<BoneSegment>& segments,
                          const Eigen::MatrixXd& visible, int joint_count, double min_distance,
                          double strength) {
  const Eigen::Index n = avatar.vertices.rows();
  if (visible.rows() != n || visible.cols() != static_cast<Eigen::Index>(segments.size()) ||
      !(min_distance > 0.0) || !(strength > 0.0))
    throw std::invalid_argument("bone_heat: visible must be #V×#S, min_distance and strength > 0");
  Eigen::VectorXd area;
  const Eigen::SparseMatrix<double> weights = cotangent_weights(avatar, area);
  // A vertex whose triangles are all degenerate still gets a little area to be heated by.
  const double area_floor = 1e-6 * std::max(area.mean(), std::numeric_limits<double>::min());

  // Multiplied through by the lumped areas M: (-L_c + M H) w_j = M H p_j stays symmetric.
  Eigen::VectorXd heat = Eigen::VectorXd::Zero(n);
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n, joint_count);
  for (Eigen::Index v = 0; v < n; ++v) {
    const double nearest = visible.row(v).minCoeff();
    if (!std::isfinite(nearest)) continue;
    const double d = std::max(nearest, min_distance);
    heat[v] = std::max(area[v], area_floor) * strength / (d * d);
    const double tie = nearest * (1.0 + kTieTolerance);
    const auto ties = static_cast<double>((visible.row(v).array() <= tie).count());
    for (std::size_t s = 0; s < segments.size(); ++s)
      if (visible(v, static_cast<Eigen::Index>(s)) <= tie)
        rhs(v, segments[s].owner) += heat[v] / ties;
  }

  // Parts where no vertex sees a segment would be singular: pinned to 0 (identity rows).
  const std::vector<char> heated = heated_parts(weights, heat);
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<std::size_t>(weights.nonZeros() + n));
  for (Eigen::Index v = 0; v < n; ++v) {
    if (!heated[static_cast<std::size_t>(v)]) {
      triplets.emplace_back(v, v, 1.0);
      continue;
    }
    double diagonal = heat[v];
    for (Eigen::SparseMatrix<double>::InnerIterator it(weights, v); it; ++it) {
      triplets.emplace_back(it.index(), v, -it.value());
      diagonal += it.value();
    }
    triplets.emplace_back(v, v, diagonal);
  }
  Eigen::SparseMatrix<double> system(n, n);
  system.setFromTriplets(triplets.begin(), triplets.end());
  LinearSolver solver;
  if (!solver.factorize(system))
    throw std::runtime_error("bone_heat: the heat system is not positive definite");
  Eigen::MatrixXd result = Eigen::MatrixXd::Zero(joint_count, n);
  for (int j = 0; j < joint_count; ++j)
    if (rhs.col(j).maxCoeff() > 0.0)
      result.row(j) = solver.solve(rhs.col(j)).cwiseMax(0.0).transpose();
  return result;
}

}  // namespace gr
