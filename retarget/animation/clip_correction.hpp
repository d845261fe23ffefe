#pragma once

#include <string>
#include <vector>

#include "core/common/interrupter.hpp"
#include "core/inflation/retarget_parameters.hpp"
#include "retarget/animation/animation_check.hpp"

namespace gr {

/// How a clip's frames were put right.
struct ClipCorrection {
  /// Per sampled frame, per garment, its morph offsets in the skin's bind space (#P×3, file
  /// units); empty matrices where skinning alone leaves the frame free.
  std::vector<std::vector<MatrixX3d>> offsets;
  std::vector<bool> corrected;  ///< per frame: skinning crossed, a correction was solved
  int corrections_failed = 0;   ///< solves that ended without a garment free of the avatar
  std::string first_failure;    ///< how the first of them ended
  int steps = 0;                ///< poses solved for, sampled frames and the steps between
  int solves = 0;               ///< of those, the ones skinning alone left crossing
  double seconds = 0.0;
};

/// Plays `clip` on the scene and, where skinning lets the garments cross the avatar, each
/// other or themselves (beyond their pairs at rest), puts the frame right: from the last
/// pose's garment, the avatar moves to the frame's (CCD bounding every motion, the IPC
/// barrier pushing the garment; inflate_avatar), then the garment is pulled toward its
/// skinned place under the same barrier, keeping its rest shape (fit_garment with
/// GarmentScene::tracked). The path starts at the rest pose; where a step of the avatar
/// moves a vertex further than `max_step` (normalized units, body ≈ 2 tall), the joints
/// are blended in smaller steps. All garments of the scene are solved together.
/// @throw Interrupted from `interrupter`.
ClipCorrection correct_clip(const AnimatedScene& scene, const ChosenClip& clip, double fps,
                            const RetargetParameters& parameters, double max_step,
                            Interrupter& interrupter = null_interrupter());

}  // namespace gr
