#pragma once

#include <optional>
#include <string>
#include <vector>

#include "garment/fit/ease.hpp"
#include "retarget/report.hpp"
#include "retarget/run/progress.hpp"
#include "retarget/scene/inferred_inputs.hpp"
#include "retarget/scene/normalization.hpp"

namespace gr {

struct InferInput {
  const Scene& scene;
  const NormalizedScene& normalized;
  const ScenePaths& paths;  ///< the source body, and whether a no-fit list was given
  ShrinkMode shrink_mode = ShrinkMode::kLevelset;  ///< skin weights are bound for skeleton
};

struct InferOptions {
  InferenceOptions inference;
  std::optional<FitMode> fit_mode;  ///< unset: ease with a source body, else tight
  std::string out_dir;              ///< where an inferred no-fit list is written
  double voxel_size =
      PipelineParameters{}.voxel_size;  ///< the fit's grid spacing (normalized units)
};

struct InferOutput {
  /// The no-fit list the run uses (welded garment vertex ids): given or inferred.
  std::vector<int> no_fit;
  /// The garment's ease on its source body (normalized units); empty without one.
  SourceEase source_ease;
  /// The source body (normalized, in the garment's frame) when one was given.
  std::optional<TriangleMesh> source_body;
  /// Skin weights for the skeleton shrink (#J×#welded avatar vertices): given, bound, or
  /// empty (nearest bone).
  Eigen::MatrixXd skin_weights;
  InferenceReport inferred;
  /// The skin weights bound to the target skeleton when none were given (a written GLB's
  /// skin takes them); empty when they were given.
  Eigen::MatrixXd bound_skin_weights() const {
    return inferred.skin_weights_inferred ? skin_weights : Eigen::MatrixXd();
  }
  EaseReport ease;
  bool source_body_posed = false;  ///< it followed the garment into the target's pose
  double binding_seconds = 0.0;
};

/// Infer: what the run needs and was not given. The no-fit list (from the source body when
/// there is one, written to out_dir/no-fit.txt), the fit mode and the garment's source ease
/// with the distance band the fit must read, and for a skeleton shrink the avatar's skin
/// weights bound to the target skeleton.
/// @throw InputError when the source body cannot be read, --fit ease has no source body,
///        or the root joint is not a joint of the skeletons; OutputError when the no-fit
///        list cannot be written; Interrupted from progress during the binding.
InferOutput run_infer(const InferInput& input, const InferOptions& options, Progress& progress);

}  // namespace gr
