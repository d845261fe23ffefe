#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/inflation/retarget_parameters.hpp"
#include "retarget/animation/animation_check.hpp"
#include "retarget/run/progress.hpp"

namespace gr {

struct AnimateInput {
  /// Per garment, its written GLB (staging) and its mesh there; one garment per file.
  const std::vector<std::string>& written_files;
  const std::vector<std::string>& written_meshes;
  const std::string& avatar;                      ///< the avatar's glTF file, as given
  const std::vector<std::string>& avatar_meshes;  ///< its meshes read (empty: the skin's)
};

struct AnimateOptions {
  std::vector<std::string> clips;  ///< as ValidateOptions::animations names them
  double fps = 30.0;
  RetargetParameters parameters;  ///< the solve's; its dhat and CCD bound the corrections
  /// A step of the avatar between two solved poses moves no vertex further (normalized
  /// units, body ≈ 2 tall); larger motions are blended in steps.
  double max_step = 0.1;
};

/// One clip: the garments played by their skins, the corrections, and the written result.
struct AnimationReport {
  ClipFindings skinned;      ///< the certified garments played by their skins alone
  int corrected_frames = 0;  ///< frames that play a correction
  int solved_frames = 0;     ///< of those, the frames a correction was solved for
  int carried_frames = 0;    ///< of those, the frames that play the last one, still free
  int morph_targets = 0;     ///< corrections written (one per solved frame)
  int steps = 0;             ///< poses solved for (frames and the steps between)
  int solves = 0;            ///< poses that needed a correction
  /// The corrections' Newton steps and time: pushes (the avatar moving) and settling.
  int push_iterations = 0;
  int settle_iterations = 0;
  double push_seconds = 0.0;
  double settle_seconds = 0.0;
  /// How far the corrections move the garment's vertices (avatar units): the mean over the
  /// corrected frames of their mean offset, and the largest offset.
  double mean_offset = 0.0;
  double max_offset = 0.0;
  int corrections_failed = 0;
  double correction_seconds = 0.0;
  ClipFindings written;     ///< the written files played, corrections included
  ClipPoses written_poses;  ///< the meshes of every frame of `written`, as checked
};

struct AnimateOutput {
  std::vector<AnimationReport> clips;
  double seconds = 0.0;
  /// Every frame of every clip free, as written.
  bool certified() const;
};

/// Animate: plays each clip on the written garments and the avatar, corrects the frames
/// where skinning lets the garments cross (correct_clip), adds the corrections to the
/// written GLBs as morph targets keyed per frame by a weights channel, with the clip's
/// joint channels, so that an engine plays the corrected garment, and checks every frame of
/// the files as written again, exactly.
/// @throw InputError for a clip that cannot be found or read, or a garment or avatar
///        without a skin; OutputError when a file cannot be written; Interrupted.
AnimateOutput run_animate(const AnimateInput& input, const AnimateOptions& options,
                          Progress& progress);

/// report.json `animation`: per clip, what skinning alone gave, the corrections and the
/// written result frame by frame.
nlohmann::ordered_json to_json(const AnimateOutput& output);

}  // namespace gr
