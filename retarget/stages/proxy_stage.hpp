#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/inflation/avatar_inflation.hpp"
#include "garment/fit/ease.hpp"
#include "garment/proxy/coarse_proxy.hpp"
#include "retarget/report.hpp"
#include "retarget/run/progress.hpp"
#include "retarget/stages/solver_scene.hpp"

namespace gr {

/// A proxy's solves, as paths for the fine garment to follow; the paths read this object,
/// which must outlive them.
class ProxyPaths {
 public:
  ProxyPaths(std::shared_ptr<const CoarseProxy> proxy, int fine_vertex_count)
      : proxy_(std::move(proxy)), fine_vertex_count_(fine_vertex_count) {}

  /// The proxy's inflation iterates ([t, Vp]) of its last attempt, spaced out and carried
  /// to the garment ([t, Vg]), with the proxy's final multipliers.
  InflationGuide inflation() const;
  /// The proxy's fit motions (Vp, from its inflated garment on), spaced out, carried to the
  /// garment
  /// (Vg) and added to `fine_start` (#Vg×3), the garment's inflated positions: the
  /// garment's own inflation ended near, not at, the proxy's carried to it.
  GuidePath fit(const MatrixX3d& fine_start) const;

  std::vector<Eigen::VectorXd> inflation_points;  ///< [t, Vp]
  std::vector<Eigen::VectorXd> fit_points;        ///< Vp, row by row
  MatrixX3d inflated;                             ///< the proxy's inflated garment (#Vp×3)
  double lambda1 = 0.0, lambda2 = 0.0;            ///< the proxy inflation's at its end

 private:
  std::shared_ptr<const CoarseProxy> proxy_;
  int fine_vertex_count_ = 0;
};

struct ProxyInput {
  const SolverScene& solver;  ///< the garment's
  /// The garment's ease on its source body for the ease fit; null: the tight fit.
  const SourceEase* source_ease = nullptr;
  /// The faces of the outfit's largest layer; 0: the garment is one layer.
  int largest_layer_faces = 0;
};

struct ProxyOptions {
  RetargetParameters parameters;
  /// The size of the largest layer's proxy (the others are decimated by the same ratio); a
  /// garment whose largest layer has more than twice this has one.
  int proxy_faces = 0;
  double max_ease_offset = 0.0;  ///< as FitOptions::max_ease_offset
};

struct ProxyOutput {
  std::optional<ProxyPaths> paths;  ///< set when the proxy solved
  ProxyReport report;
};

/// Coarse to fine, the coarse part: for a garment (an outfit: whose largest layer has) of
/// more than twice options.proxy_faces faces, decimates it (make_coarse_proxy) and runs the
/// inflation and the fit on the proxy, recording their iterates for the garment's own
/// solves to follow. No paths when the garment is small enough, has no valid proxy, or the
/// proxy's solves fail; the garment is then solved directly, and the report says why. An
/// outfit of ordinary layers is solved directly: a proxy pays where each layer is dense, and
/// one of several layers together keeps too little of each one's folds and ease.
/// @throw Interrupted from progress (the run's limits).
ProxyOutput run_proxy(const ProxyInput& input, const ProxyOptions& options, Progress& progress);

}  // namespace gr
