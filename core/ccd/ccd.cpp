#include "core/ccd/ccd.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "core/broad_phase/pair_separation.hpp"
#include "core/ccd/additive_ccd.hpp"

namespace gr {
namespace {

/// Step bound for candidate k (point–triangle first, then edge–edge), at most t_max.
double pair_step(const Candidates& candidates, std::size_t k, const Eigen::Ref<const MatrixX3d>& V0,
                 const Eigen::Ref<const MatrixX3d>& V1, const CcdOptions& options, double t_max) {
  const bool edge_edge = k >= candidates.point_triangle.size();
  std::array<int, 4> ids;
  if (!edge_edge) {
    const PointTriangleCandidate& c = candidates.point_triangle[k];
    ids = {c.point, c.triangle[0], c.triangle[1], c.triangle[2]};
  } else {
    const EdgeEdgeCandidate& c = candidates.edge_edge[k - candidates.point_triangle.size()];
    ids = {c.edge_a[0], c.edge_a[1], c.edge_b[0], c.edge_b[1]};
  }
  std::array<Vector3d, 4> x0, x1;
  for (int i = 0; i < 4; ++i) {
    x0[i] = V0.row(ids[i]).transpose();
    x1[i] = V1.row(ids[i]).transpose();
  }
  // Primitives whose swept hulls stay further apart than the absolute separation and than
  // the starting distance's separation cannot come that close: no narrow phase needed.
  const double d0_upper = (x0[0] - x0[edge_edge ? 2 : 1]).norm();  // any point pair bounds d0
  const double needed = std::max(options.min_separation, options.min_separation_ratio * d0_upper);
  const double gap = pair_separation_lower_bound(x0, x1, edge_edge ? 2 : 1, needed);
  if (gap > options.min_separation && gap > 0.0 && gap >= options.min_separation_ratio * d0_upper)
    return t_max;
  return edge_edge ? edge_edge_ccd(x0, x1, options, t_max)
                   : point_triangle_ccd(x0, x1, options, t_max);
}

void check_arguments(const Eigen::Ref<const MatrixX3d>& V0, const Eigen::Ref<const MatrixX3d>& V1,
                     const CcdOptions& options) {
  if (V0.rows() != V1.rows())
    throw std::invalid_argument("CCD start and end positions have different vertex counts");
  if (!(options.min_separation_ratio > 0.0 && options.min_separation_ratio < 1.0) ||
      !(options.min_separation >= 0.0) || options.max_iterations < 1)
    throw std::invalid_argument(
        "CCD options: min_separation_ratio must be in (0, 1), min_separation >= 0, "
        "max_iterations >= 1");
}

}  // namespace

double max_step(const Candidates& swept_candidates, const Eigen::Ref<const MatrixX3d>& V0,
                const Eigen::Ref<const MatrixX3d>& V1, const CcdOptions& options) {
  check_arguments(V0, V1, options);
  // Each task passes its running minimum down as the pair's t_max: a pair stops as soon
  // as it is known not to lower the minimum (the result is the same in any order).
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, swept_candidates.size(), 64), 1.0,
      [&](const tbb::blocked_range<std::size_t>& range, double step) {
        for (std::size_t k = range.begin(); k != range.end() && step > 0.0; ++k)
          step = std::min(step, pair_step(swept_candidates, k, V0, V1, options, step));
        return step;
      },
      [](double a, double b) { return std::min(a, b); });
}

std::vector<double> vertex_steps(const Candidates& swept_candidates,
                                 const Eigen::Ref<const MatrixX3d>& V0,
                                 const Eigen::Ref<const MatrixX3d>& V1, const CcdOptions& options) {
  check_arguments(V0, V1, options);
  std::vector<double> pair_steps(swept_candidates.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pair_steps.size(), 64),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t k = range.begin(); k != range.end(); ++k)
                        pair_steps[k] = pair_step(swept_candidates, k, V0, V1, options, 1.0);
                    });
  std::vector<double> steps(static_cast<std::size_t>(V0.rows()), 1.0);
  const auto lower = [&](int vertex, double step) {
    double& bound = steps[static_cast<std::size_t>(vertex)];
    bound = std::min(bound, step);
  };
  const std::size_t point_triangle = swept_candidates.point_triangle.size();
  for (std::size_t k = 0; k < pair_steps.size(); ++k) {
    if (pair_steps[k] >= 1.0) continue;
    if (k < point_triangle) {
      const PointTriangleCandidate& c = swept_candidates.point_triangle[k];
      lower(c.point, pair_steps[k]);
      for (const int v : c.triangle) lower(v, pair_steps[k]);
    } else {
      const EdgeEdgeCandidate& c = swept_candidates.edge_edge[k - point_triangle];
      for (const int v : c.edge_a) lower(v, pair_steps[k]);
      for (const int v : c.edge_b) lower(v, pair_steps[k]);
    }
  }
  return steps;
}

}  // namespace gr
