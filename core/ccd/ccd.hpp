#pragma once

#include "core/candidates/candidates.hpp"

namespace gr {

struct CcdOptions {
  /// No pair may come closer than this fraction of its distance at the start of the
  /// step (keeps steps from landing at zero distance), in (0, 1).
  double min_separation_ratio = 0.1;
  /// Absolute floor on the separation, normalized scene units.
  double min_separation = 0.0;
  /// Iteration budget per pair; when exhausted the pair's step is the last safe bound.
  int max_iterations = 10000;
};

/// Largest fraction alpha in [0, 1] of the linear motion V0 → V1 (#V×3 stacked) such that
/// no candidate pair comes closer than the minimum separation anywhere in [0, alpha].
/// Conservative: never larger than the true time of contact. 0 when a pair starts at or
/// below the separation and approaches; a pair that starts below min_separation but does
/// not approach is held to min_separation_ratio times its starting distance only. Additive
/// CCD per pair (core/ccd/additive_ccd.hpp), pairs in parallel.
/// @throw std::invalid_argument for options out of range or V0, V1 of different sizes.
double max_step(const Candidates& swept_candidates, const Eigen::Ref<const MatrixX3d>& V0,
                const Eigen::Ref<const MatrixX3d>& V1, const CcdOptions& options = {});

/// Per vertex (row of V0), the smallest of max_step's per-pair bounds over the candidate
/// pairs it belongs to, 1 where none cuts the motion: which parts of a motion meet
/// something. The minimum over all vertices is max_step's result.
/// @throw std::invalid_argument as max_step.
std::vector<double> vertex_steps(const Candidates& swept_candidates,
                                 const Eigen::Ref<const MatrixX3d>& V0,
                                 const Eigen::Ref<const MatrixX3d>& V1,
                                 const CcdOptions& options = {});

}  // namespace gr
