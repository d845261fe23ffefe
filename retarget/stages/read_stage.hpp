#pragma once

#include <optional>

#include "retarget/run/progress.hpp"
#include "retarget/scene/garment_pose.hpp"
#include "retarget/scene/scene.hpp"
#include "retarget/scene/shrink_avatar.hpp"

namespace gr {

struct ReadInput {
  ScenePaths paths;
};

struct ReadOptions {
  RunLimits limits;
  std::optional<ShrinkMode> shrink_mode;  ///< unset: skeleton with skeletons, else levelset
  PoseMode pose = PoseMode::kTarget;
  SkinningMethod pose_skinning = SkinningMethod::kLinearBlend;
};

struct ReadOutput {
  Scene scene;
  ShrinkMode shrink_mode = ShrinkMode::kLevelset;
  /// Peak memory the run is estimated to take (estimated_peak_memory_mb), MiB.
  double estimated_memory_mb = 0.0;
  PoseReport pose;  ///< whether the garment was turned into the target's pose
  double seconds = 0.0;
};

/// Read: the scene's files, checked against the limits, the garment turned into the
/// target's pose (pose_garment), and the shrink mode.
/// @throw InputError for bad or missing files, a scene beyond options.limits, or a
///        skeleton shrink without both skeletons.
ReadOutput run_read(const ReadInput& input, const ReadOptions& options, Progress& progress);

}  // namespace gr
