#include "retarget/stages/proxy_stage.hpp"

#include <cmath>

#include <fmt/format.h>

#include "core/fit/garment_fit.hpp"

namespace gr {

namespace {

/// Consecutive points of a followed path are at least this far apart (the largest garment
/// vertex motion between them, normalized units), the last point aside: each motion costs
/// a CCD pass over the whole garment, and near contact the proxy's own steps are far
/// shorter than this. The garment's CCD still bounds every motion.
constexpr double kGuideSpacing = 0.02;

/// The garment holds back where the proxy's motions run it into itself (its folds, finer
/// than the proxy's) or, in the fit, into the avatar, fading out over this many proxy edge
/// lengths.
constexpr double kFadeEdges = 4.0;

/// Newton steps of the garment's own, pulled towards the point, that each recovery from a
/// motion cut below a tenth may take before it is tried again (GuidePath::recovery_steps):
/// a few steps slide it around a fold or a bump the proxy did not have, which costs far
/// less than leaving the path.
constexpr int kRecoverySteps = 8;

/// The indices of `points` (dofs of `layout`) a garment follows: thinned to kGuideSpacing.
std::vector<int> spaced_points(const std::vector<Eigen::VectorXd>& points,
                               const DofLayout& layout) {
  std::vector<int> kept;
  const auto count = static_cast<int>(points.size());
  int previous = 0;
  for (int k = 0; k < count; ++k) {
    const auto motion = layout.garment(points[static_cast<std::size_t>(k)]) -
                        layout.garment(points[static_cast<std::size_t>(previous)]);
    const double length = motion.rows() > 0 ? motion.rowwise().norm().maxCoeff() : 0.0;
    if (k + 1 == count || length >= kGuideSpacing) {
      kept.push_back(k);
      previous = k;
    }
  }
  return kept;
}

/// Keeps each point a proxy's solve accepts (its path, for the garment to follow) and
/// passes everything on to the run's progress.
class PathRecorder final : public ForwardingInterrupter {
 public:
  PathRecorder(Interrupter& next, std::vector<Eigen::VectorXd>& points)
      : ForwardingInterrupter(next), points_(points) {}

  void step(const SolverStep& step) override {
    next().step(step);
    points_.push_back(*step.point);
  }

 private:
  std::vector<Eigen::VectorXd>& points_;
};

}  // namespace

InflationGuide ProxyPaths::inflation() const {
  InflationGuide guide;
  guide.lambda1 = lambda1;
  guide.lambda2 = lambda2;
  const DofLayout proxy_layout{static_cast<int>(proxy_->scene.garment.vertices.rows()), true};
  const DofLayout fine_layout{fine_vertex_count_, true};
  const auto kept =
      std::make_shared<const std::vector<int>>(spaced_points(inflation_points, proxy_layout));
  guide.path.size = static_cast<int>(kept->size());
  guide.path.fade_length = kFadeEdges * proxy_->edge_length;
  guide.path.recovery_steps = kRecoverySteps;
  guide.path.point = [this, proxy_layout, fine_layout, kept](int index, Eigen::VectorXd& point) {
    const Eigen::VectorXd& x =
        inflation_points[static_cast<std::size_t>((*kept)[static_cast<std::size_t>(index)])];
    point = fine_layout.pack(proxy_layout.t(x), proxy_->embedding.carry(proxy_layout.garment(x)));
  };
  return guide;
}

GuidePath ProxyPaths::fit(const MatrixX3d& fine_start) const {
  GuidePath path;
  const DofLayout proxy_layout{static_cast<int>(proxy_->scene.garment.vertices.rows()), false};
  const DofLayout fine_layout{fine_vertex_count_, false};
  const auto kept =
      std::make_shared<const std::vector<int>>(spaced_points(fit_points, proxy_layout));
  const auto offset =
      std::make_shared<const MatrixX3d>(fine_start - proxy_->embedding.carry(inflated));
  path.size = static_cast<int>(kept->size());
  path.fade_length = kFadeEdges * proxy_->edge_length;
  path.recovery_steps = kRecoverySteps;
  path.point = [this, proxy_layout, fine_layout, kept, offset](int index, Eigen::VectorXd& point) {
    const Eigen::VectorXd& x =
        fit_points[static_cast<std::size_t>((*kept)[static_cast<std::size_t>(index)])];
    point = fine_layout.pack(1.0, proxy_->embedding.carry(proxy_layout.garment(x)) + *offset);
  };
  return path;
}

ProxyOutput run_proxy(const ProxyInput& input, const ProxyOptions& options, Progress& progress) {
  const StageTimer timer;
  ProxyOutput out;
  ProxyReport& report = out.report;
  const GarmentScene& fine = input.solver.scene;
  const auto faces = static_cast<int>(fine.garment.faces.rows());
  const int layer_faces = input.largest_layer_faces > 0 ? input.largest_layer_faces : faces;
  if (options.proxy_faces <= 0 || layer_faces <= 2 * options.proxy_faces) {
    report.reason = options.proxy_faces <= 0 ? "coarse to fine is off (--proxy-faces 0)"
                    : input.largest_layer_faces > 0
                        ? fmt::format(
                              "the largest layer's {} faces are at most twice "
                              "--proxy-faces {}",
                              layer_faces, options.proxy_faces)
                        : fmt::format("{} faces are at most twice --proxy-faces {}", faces,
                                      options.proxy_faces);
    return out;
  }
  const auto not_used = [&](std::string reason) {
    progress.log("proxy", "solving the garment directly: {}", reason);
    report.reason = std::move(reason);
    report.seconds = timer.seconds();
    return out;
  };
  std::string why_not;
  const auto proxy_faces =
      static_cast<int>(std::lround(static_cast<double>(options.proxy_faces) * faces / layer_faces));
  std::optional<CoarseProxy> made = make_coarse_proxy(fine, proxy_faces, why_not);
  if (!made) return not_used(why_not);
  const auto proxy = std::make_shared<const CoarseProxy>(std::move(*made));
  report.faces = static_cast<int>(proxy->scene.garment.faces.rows());
  const double clearance = proxy->clearance;
  report.clearance = clearance;
  progress.log(
      "proxy",
      "{} faces decimated to {}, the garment within {:.3g} of it, clearance {:.3g} ({:.2f} s)",
      faces, report.faces, proxy->embedding.max_offset(), clearance, timer.seconds());

  ProxyPaths paths(proxy, static_cast<int>(fine.garment.vertices.rows()));
  const RetargetParameters& parameters = options.parameters;
  progress.start("proxy inflate");
  PathRecorder inflation_path(progress, paths.inflation_points);
  // A reset sends the proxy back to its start: only the last attempt is a path.
  const InflationCallback on_round = [&](const InflationRound& round) {
    if (round.reset) paths.inflation_points.clear();
  };
  // The proxy's barrier reaches as much further as the garment lies from it, so that the
  // garment carried along its inflation keeps clear of the growing avatar too. (Further
  // still, by the whole clearance, lengthens the proxy's paths and so the garment's.)
  RetargetParameters inflation_parameters = parameters;
  inflation_parameters.dhat += proxy->embedding.max_offset();
  const InflationResult inflation =
      inflate_avatar(proxy->scene, inflation_parameters, on_round, inflation_path);
  report.inflate_newton_iterations = inflation.newton_iterations;
  if (!inflation.succeeded()) return not_used("the proxy's inflation failed: " + inflation.message);
  // The snap to t = 1 is the last point of the path.
  const DofLayout proxy_inflation{static_cast<int>(proxy->scene.garment.vertices.rows()), true};
  paths.inflation_points.push_back(proxy_inflation.pack(1.0, inflation.garment));
  paths.inflated = inflation.garment;
  paths.lambda1 = inflation.lambda1;
  paths.lambda2 = inflation.lambda2;

  GarmentScene fit_scene = proxy->scene;
  fit_scene.fit_offsets.assign(static_cast<std::size_t>(fit_scene.garment.vertices.rows()), 0.0);
  if (input.source_ease) {
    SourceEase proxy_ease;
    for (const int v : proxy->fine_vertex)
      proxy_ease.distance.push_back(input.source_ease->distance[static_cast<std::size_t>(v)]);
    fit_scene.fit_offsets =
        ease_targets(fit_scene.garment, inflation.garment, proxy_ease, options.max_ease_offset)
            .offsets;
  }
  // The proxy fits that much further out than the garment will, so that the garment carried
  // with it stays clear of the avatar; the garment's own steps then close the gap. (The
  // fit's barrier keeps its width: a wider one would hold the proxy off the offsets.)
  for (double& offset : fit_scene.fit_offsets) offset += clearance;
  progress.start("proxy fit");
  PathRecorder fit_path(progress, paths.fit_points);
  const FitResult fit = fit_garment(fit_scene, inflation.garment, parameters, fit_path);
  report.fit_newton_iterations = fit.solve.iterations;
  if (fit.solve.status == SolverStatus::kNonFiniteEnergy)
    return not_used("the proxy's fit failed: " + fit.solve.message);
  report.used = true;
  report.seconds = timer.seconds();
  progress.log("proxy", "inflated in {} and fitted in {} Newton steps ({:.2f} s)",
               report.inflate_newton_iterations, report.fit_newton_iterations, report.seconds);
  out.paths = std::move(paths);
  return out;
}

}  // namespace gr
