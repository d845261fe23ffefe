#include "core/potentials/barrier_potential.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "core/barrier/barrier.hpp"
#include "core/broad_phase/pair_separation.hpp"
#include "core/common/errors.hpp"
#include "core/common/psd_projection.hpp"
#include "core/distance/edge_edge_distance.hpp"
#include "core/distance/edge_edge_mollifier.hpp"
#include "core/distance/point_triangle_distance.hpp"
#include "core/potentials/stencil_matrix_sum.hpp"

namespace gr {
namespace {

/// Candidates per parallel task: enough work to amortize scheduling, and a fixed split
/// so sums come out the same on any thread count.
constexpr std::size_t kGrain = 256;

/// Candidate k of the stacked list (point–triangle first, then edge–edge) as a stencil.
struct PairStencil {
  std::array<int, 4> vertices;
  bool edge_edge;
};

PairStencil stencil_of(const Candidates& candidates, std::size_t k) {
  if (k < candidates.point_triangle.size()) {
    const PointTriangleCandidate& c = candidates.point_triangle[k];
    return {{c.point, c.triangle[0], c.triangle[1], c.triangle[2]}, false};
  }
  const EdgeEdgeCandidate& c = candidates.edge_edge[k - candidates.point_triangle.size()];
  return {{c.edge_a[0], c.edge_a[1], c.edge_b[0], c.edge_b[1]}, true};
}

std::array<Vector3d, 4> gather(const Eigen::Ref<const MatrixX3d>& V,
                               const std::array<int, 4>& ids) {
  return {V.row(ids[0]).transpose(), V.row(ids[1]).transpose(), V.row(ids[2]).transpose(),
          V.row(ids[3]).transpose()};
}

/// Squared distance of a pair and, when asked, its derivatives on the 12-stencil.
double pair_distance_sq(const PairStencil& pair, const std::array<Vector3d, 4>& x,
                        Vector12d* gradient, Matrix12d* hessian) {
  const DistanceStencil stencil =
      pair.edge_edge ? edge_edge_stencil(edge_edge_distance_type(x[0], x[1], x[2], x[3]))
                     : point_triangle_stencil(point_triangle_distance_type(x[0], x[1], x[2], x[3]));
  return stencil_distance_sq<4>(stencil, x, gradient, hessian);
}

/// PSD projection of a translation-invariant stencil Hessian. Every pair energy depends
/// only on the differences x_i - x_0 (i = 1..3), so H = S^T H9 S with H9 the lower-right
/// 9×9 block; projecting H9 and mapping back gives a PSD matrix, equal to H when H is PSD
/// already, for an eigen-decomposition of 9×9 instead of 12×12 (about 2.4 times cheaper).
Matrix12d project_stencil_to_psd(const Matrix12d& H) {
  const Matrix9d H9 = project_to_psd(Matrix9d(H.bottomRightCorner<9, 9>()));
  Matrix12d out;
  out.bottomRightCorner<9, 9>() = H9;
  for (int j = 0; j < 3; ++j) {
    // Row/column blocks of vertex 0 are minus the sums over the others.
    Eigen::Matrix3d column_sum = Eigen::Matrix3d::Zero();
    for (int i = 0; i < 3; ++i) column_sum += H9.block<3, 3>(3 * i, 3 * j);
    out.block<3, 3>(0, 3 + 3 * j) = -column_sum;
    out.block<3, 3>(3 + 3 * j, 0) = -column_sum.transpose();
  }
  Eigen::Matrix3d total = Eigen::Matrix3d::Zero();
  for (int j = 0; j < 3; ++j) total -= out.block<3, 3>(0, 3 + 3 * j);
  out.topLeftCorner<3, 3>() = total;
  return out;
}

}  // namespace

BarrierPotential::BarrierPotential(double dhat, const Eigen::Ref<const MatrixX3d>& rest_vertices)
    : dhat_(dhat), rest_vertices_(rest_vertices) {
  if (!(dhat > 0.0) || !std::isfinite(dhat))
    throw InputError("", 0, "barrier support dhat must be positive and finite");
}

BarrierPotential::PairEnergy BarrierPotential::pair_energy(const Candidates& candidates,
                                                           std::size_t k,
                                                           const Eigen::Ref<const MatrixX3d>& V,
                                                           Vector12d* gradient,
                                                           Matrix12d* hessian) const {
  const PairStencil pair = stencil_of(candidates, k);
  const std::array<Vector3d, 4> x = gather(V, pair.vertices);
  const double xhat = dhat_ * dhat_;
  // Most candidates (swept ones above all) are far apart: a separation bound already says
  // so, which is much cheaper than classifying the closest features.
  if (pair_separation_lower_bound(x, pair.edge_edge ? 2 : 1, dhat_) >= dhat_) return {0.0, false};
  const bool derivatives = gradient || hessian;
  Vector12d gd;
  Matrix12d Hd;
  const double d_sq =
      pair_distance_sq(pair, x, derivatives ? &gd : nullptr, hessian ? &Hd : nullptr);
  if (d_sq >= xhat) return {0.0, false};
  if (d_sq <= 0.0) return {std::numeric_limits<double>::infinity(), false};

  const double b = barrier(d_sq, xhat);
  const double db = derivatives ? barrier_first_derivative(d_sq, xhat) : 0.0;
  const double d2b = hessian ? barrier_second_derivative(d_sq, xhat) : 0.0;
  if (!pair.edge_edge) {
    if (gradient) *gradient = db * gd;
    if (hessian) *hessian = d2b * gd * gd.transpose() + db * Hd;
    return {b, true};
  }
  // Edge–edge: E = m b with m the mollifier of |ea × eb|² against the rest threshold.
  const std::array<Vector3d, 4> rest = gather(rest_vertices_, pair.vertices);
  const double eps = edge_edge_mollifier_threshold(rest[0], rest[1], rest[2], rest[3]);
  if (!(eps > 0.0)) return {0.0, false};  // a zero-length rest edge: parallel to everything
  Vector12d gm;
  Matrix12d Hm;
  const double m = edge_edge_mollifier(x[0], x[1], x[2], x[3], eps, derivatives ? &gm : nullptr,
                                       hessian ? &Hm : nullptr);
  if (gradient) *gradient = b * gm + m * db * gd;
  if (hessian) {
    const Matrix12d cross = gm * gd.transpose();
    *hessian =
        b * Hm + db * (cross + cross.transpose()) + m * (d2b * gd * gd.transpose() + db * Hd);
  }
  return {m * b, true};
}

double BarrierPotential::value(const Candidates& candidates,
                               const Eigen::Ref<const MatrixX3d>& V) const {
  return tbb::parallel_deterministic_reduce(
      tbb::blocked_range<std::size_t>(0, candidates.size(), kGrain), 0.0,
      [&](const tbb::blocked_range<std::size_t>& range, double sum) {
        for (std::size_t k = range.begin(); k != range.end(); ++k)
          sum += pair_energy(candidates, k, V, nullptr, nullptr).value;
        return sum;
      },
      std::plus<double>());
}

Eigen::VectorXd BarrierPotential::gradient(const Candidates& candidates,
                                           const Eigen::Ref<const MatrixX3d>& V) const {
  // Local gradients in parallel, scattered in candidate order (deterministic sums).
  const std::size_t count = candidates.size();
  std::vector<Vector12d> local(count);
  std::vector<char> active(count, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, kGrain), [&](const auto& range) {
    for (std::size_t k = range.begin(); k != range.end(); ++k) {
      active[k] = pair_energy(candidates, k, V, &local[k], nullptr).active;
    }
  });
  Eigen::VectorXd g = Eigen::VectorXd::Zero(3 * V.rows());
  for (std::size_t k = 0; k < count; ++k) {
    if (!active[k]) continue;
    const PairStencil pair = stencil_of(candidates, k);
    for (int i = 0; i < 4; ++i) g.segment<3>(3 * pair.vertices[i]) += local[k].segment<3>(3 * i);
  }
  return g;
}

Eigen::SparseMatrix<double> BarrierPotential::hessian(const Candidates& candidates,
                                                      const Eigen::Ref<const MatrixX3d>& V,
                                                      bool project_psd) const {
  // Active stencils per fixed chunk of candidates, joined in chunk order.
  const std::size_t count = candidates.size();
  const std::size_t chunks = (count + kGrain - 1) / kGrain;
  std::vector<std::vector<StencilMatrix>> per_chunk(chunks);
  tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t chunk) {
    std::vector<StencilMatrix>& out = per_chunk[chunk];
    const std::size_t end = std::min(count, (chunk + 1) * kGrain);
    StencilMatrix s;
    for (std::size_t k = chunk * kGrain; k < end; ++k) {
      if (!pair_energy(candidates, k, V, nullptr, &s.matrix).active) continue;
      if (project_psd) s.matrix = project_stencil_to_psd(s.matrix);
      s.vertices = stencil_of(candidates, k).vertices;
      out.push_back(s);
    }
  });
  std::vector<StencilMatrix> stencils;
  std::size_t total = 0;
  for (const auto& chunk : per_chunk) total += chunk.size();
  stencils.reserve(total);
  for (const auto& chunk : per_chunk) stencils.insert(stencils.end(), chunk.begin(), chunk.end());
  return assemble_stencil_matrices(static_cast<int>(V.rows()), stencils);
}

double BarrierPotential::minimum_distance(const Candidates& candidates,
                                          const Eigen::Ref<const MatrixX3d>& V) const {
  const double min_sq = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, candidates.size(), kGrain),
      std::numeric_limits<double>::infinity(),
      [&](const tbb::blocked_range<std::size_t>& range, double best) {
        for (std::size_t k = range.begin(); k != range.end(); ++k) {
          const PairStencil pair = stencil_of(candidates, k);
          best = std::min(best, pair_distance_sq(pair, gather(V, pair.vertices), nullptr, nullptr));
        }
        return best;
      },
      [](double a, double b) { return std::min(a, b); });
  return std::sqrt(min_sq);
}

}  // namespace gr
