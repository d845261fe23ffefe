#pragma once

#include <string>
#include <vector>

#include "core/common/interrupter.hpp"
#include "core/inflation/retarget_parameters.hpp"
#include "retarget/animation/animation_check.hpp"

namespace gr {

/// How a clip's frames were put right.
struct ClipCorrection {
  /// The corrections as morph targets: per target, per garment, its offsets in the skin's
  /// bind space (#P×3, file units).
  std::vector<std::vector<MatrixX3d>> targets;
  /// Per sampled frame, the target it plays; -1 where skinning alone leaves it free.
  std::vector<int> target_of_frame;
  int solved_frames = 0;       ///< frames whose target was solved for
  int carried_frames = 0;      ///< frames that play the last target, still free with it
  int corrections_failed = 0;  ///< solves that ended without a garment free of the avatar
  std::string first_failure;   ///< how the first of them ended
  int steps = 0;               ///< poses solved for, sampled frames and the steps between
  int solves = 0;              ///< of those, the ones skinning alone left crossing
  int push_iterations = 0;     ///< Newton steps of the pushes (the avatar moving), summed
  int settle_iterations = 0;   ///< Newton steps of the garment settling, summed
  double push_seconds = 0.0;
  double settle_seconds = 0.0;
  double seconds = 0.0;
};

/// Plays `clip` on the scene and, where skinning lets the garments cross the avatar, each
/// other or themselves (beyond their pairs at rest), puts the frame right. The last
/// correction, carried into the frame's pose by the skin, is kept where it leaves the
/// frame free (checked exactly); otherwise, from the last pose's garment, the avatar moves to the
/// frame's (CCD bounding every motion, the IPC barrier pushing the garment; inflate_avatar), then
/// the garment is pulled toward its skinned place under the same barrier, keeping its rest shape
/// (fit_garment with GarmentScene::tracked). The path starts at the rest pose; where a step of the
/// avatar moves a vertex further than `max_step` (normalized units, body ≈ 2 tall), the joints are
/// blended in smaller steps, each only pushing the garment clear; the frame's own pose settles
/// it. All garments of the scene are solved together.
/// @throw Interrupted from `interrupter`.
/// @param skinning_alone the clip played by skinning alone (check_clip on the same scene,
///        clip and fps): its free frames need no correction.
ClipCorrection correct_clip(const AnimatedScene& scene, const ChosenClip& clip, double fps,
                            const ClipFindings& skinning_alone,
                            const RetargetParameters& parameters, double max_step,
                            Interrupter& interrupter = null_interrupter());

}  // namespace gr
