#include "retarget/stages/read_stage.hpp"

#include "core/common/errors.hpp"

namespace gr {

ReadOutput run_read(const ReadInput& input, const ReadOptions& options, Progress& progress) {
  const StageTimer timer;
  ReadOutput out;
  out.scene = load_scene(input.paths);
  out.estimated_memory_mb = require_within_limits(out.scene, options.limits);
  out.pose = pose_garment(out.scene, options.pose, options.pose_skinning);
  const bool has_skeletons = out.scene.source_skeleton.has_value();
  out.shrink_mode =
      options.shrink_mode.value_or(has_skeletons ? ShrinkMode::kSkeleton : ShrinkMode::kLevelset);
  if (out.shrink_mode == ShrinkMode::kSkeleton && !has_skeletons)
    throw InputError(input.paths.avatar, 0,
                     "skeleton shrink needs --source-skeleton and --target-skeleton");
  if (out.pose.posed)
    progress.log("pose",
                 "garment turned into the target's pose ({} skinning, {} joints, up to "
                 "{:.0f} degrees): edge change mean {:.3f}, p95 {:.3f}",
                 to_string(out.pose.method), out.pose.joints, out.pose.largest_turn_degrees,
                 out.pose.mean_edge_change, out.pose.p95_edge_change);
  if (out.pose.posed && out.pose.untangled_pairs > 0)
    progress.log("pose", "{} face pairs the turn made cross were pushed apart",
                 out.pose.untangled_pairs);
  const bool skinned = out.scene.garment_gltf && out.scene.garment_gltf->skin;
  if (!out.pose.posed && out.pose.mode == PoseMode::kTarget && skinned)
    progress.log("pose", "the garment keeps its pose: {}", out.pose.reason);
  out.seconds = timer.seconds();
  return out;
}

}  // namespace gr
