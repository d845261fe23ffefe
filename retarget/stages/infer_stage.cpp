#include "retarget/stages/infer_stage.hpp"

#include <algorithm>

#include "core/common/errors.hpp"
#include "shrink/level_set/signed_distance_grid.hpp"

namespace gr {

namespace {

/// The ease fit reads the avatar's distance this far out at most (normalized units): twice
/// the ease of a roomy coat's fitted vertices on the shared source bodies.
constexpr double kMaxEaseBand = 0.3;

/// The fit mode, and the garment's ease on its source body (normalized; null: none given).
/// The distance band the fit reads is widened to reach every target (ease up to twice the
/// largest source ease of a fitted vertex).
SourceEase infer_ease(const InferInput& input, const InferOptions& options,
                      const std::vector<int>& no_fit, const TriangleMesh* body, EaseReport& ease,
                      Progress& progress) {
  ease.source_known = body != nullptr;
  ease.fit = options.fit_mode.value_or(ease.source_known ? FitMode::kEase : FitMode::kTight);
  ease.distance_band = kDistanceBand;
  ease.max_offset = 0.0;
  if (!ease.source_known) {
    if (ease.fit == FitMode::kEase)
      throw InputError(input.paths.garment, 0,
                       "--fit ease needs the garment's source body (--source-body)");
    if (!options.fit_mode)
      progress.warn(
          "no --source-body: the fit pulls the garment onto the avatar (tight); give the body "
          "the garment was made on to keep its ease");
    return {};
  }
  SourceEase source = measure_source_ease(input.normalized.garment, *body);
  ease.filled_vertices = source.filled;
  if (ease.fit == FitMode::kTight) return source;
  std::vector<bool> listed(source.distance.size(), false);
  for (const int v : no_fit) listed[static_cast<std::size_t>(v)] = true;
  double largest = 0.0;
  for (std::size_t v = 0; v < source.distance.size(); ++v)
    if (!listed[v]) largest = std::max(largest, source.distance[v]);
  constexpr double kBandVoxels = 4.0;  // the interpolant reads 2 voxels each side
  ease.distance_band =
      std::clamp(2.0 * largest + kBandVoxels * options.voxel_size, kDistanceBand, kMaxEaseBand);
  ease.max_offset = ease.distance_band - kBandVoxels * options.voxel_size;
  progress.log("fit",
               "ease from the source body: largest {:.4g}, {} vertices over cuts, "
               "distance band {:.3g}",
               largest, source.filled, ease.distance_band);
  return source;
}

}  // namespace

InferOutput run_infer(const InferInput& input, const InferOptions& options, Progress& progress) {
  InferOutput out;
  // The source body gives the no-fit inference and the ease: read once.
  std::optional<TriangleMesh>& source_body = out.source_body;
  if (source_body_given(input.paths))
    source_body =
        read_source_body(input.paths, input.scene, input.normalized, &out.source_body_posed);
  if (source_body && input.scene.garment_pose && !out.source_body_posed)
    progress.warn(
        "the source body does not have the garment's skin: it keeps its pose while the garment "
        "was turned into the target's, so the ease measured on it is off (give --pose as-given)");
  out.no_fit = no_fit_for_run(input.scene, input.normalized, no_fit_given(input.paths),
                              source_body ? &*source_body : nullptr, options.out_dir,
                              options.inference, out.inferred);
  out.source_ease = infer_ease(input, options, out.no_fit, source_body ? &*source_body : nullptr,
                               out.ease, progress);
  progress.start("read");
  progress.check();
  if (input.shrink_mode != ShrinkMode::kSkeleton) {
    out.skin_weights = input.scene.skin_weights;
    return out;
  }
  const StageTimer timer;
  InferenceOptions inference = options.inference;
  inference.binding_options.interrupter = &progress;
  out.skin_weights =
      skin_weights_for_shrink(input.scene, input.normalized, inference, out.inferred);
  out.inferred.binding_options.interrupter = nullptr;
  out.binding_seconds = timer.seconds();
  if (out.inferred.skin_weights_inferred)
    progress.log("shrink", "skin weights inferred: {} binding in {:.2f} s",
                 out.inferred.binding_method, out.inferred.binding.seconds);
  return out;
}

}  // namespace gr
