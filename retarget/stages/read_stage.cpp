#include "retarget/stages/read_stage.hpp"

#include "core/common/errors.hpp"

namespace gr {

ReadOutput run_read(const ReadInput& input, const ReadOptions& options, Progress&) {
  const StageTimer timer;
  ReadOutput out;
  out.scene = load_scene(input.paths);
  out.estimated_memory_mb = require_within_limits(out.scene, options.limits);
  const bool has_skeletons = out.scene.source_skeleton.has_value();
  out.shrink_mode =
      options.shrink_mode.value_or(has_skeletons ? ShrinkMode::kSkeleton : ShrinkMode::kLevelset);
  if (out.shrink_mode == ShrinkMode::kSkeleton && !has_skeletons)
    throw InputError(input.paths.avatar, 0,
                     "skeleton shrink needs --source-skeleton and --target-skeleton");
  out.seconds = timer.seconds();
  return out;
}

}  // namespace gr
