#include "retarget/stages/animate_stage.hpp"

#include <algorithm>
#include <map>

#include "core/common/errors.hpp"
#include "core/common/stopwatch.hpp"
#include "core/io/gltf_document.hpp"
#include "retarget/animation/clip_correction.hpp"

namespace gr {

namespace {

/// The channels of `clip` that drive a skin as `binding` matched them: what an engine
/// must play for the garment to move as it was checked.
AnimationClip bound_channels(const AnimationClip& clip, const ClipBinding& binding) {
  AnimationClip kept = clip;
  kept.channels.clear();
  for (const auto& slots : binding.channels)
    for (const int channel : slots)
      if (channel >= 0) kept.channels.push_back(clip.channels[static_cast<std::size_t>(channel)]);
  return kept;
}

/// A weights channel that turns on each sampled frame's target, and all others off, from
/// half a frame before it to half a frame before the next (STEP keys): a player that
/// samples at a frame's time, rounded either way (keyframe times are 32-bit floats), meets
/// that frame's correction.
AnimationChannel frame_weights(const std::string& node, const std::vector<double>& times,
                               double fps, const std::vector<int>& target_of_frame,
                               int target_count) {
  AnimationChannel channel;
  channel.node = node;
  channel.path = ChannelPath::kWeights;
  channel.interpolation = KeyInterpolation::kStep;
  for (const double time : times) channel.times.push_back(std::max(time - 0.5 / fps, 0.0));
  channel.values = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(times.size()), target_count);
  for (std::size_t f = 0; f < times.size(); ++f)
    if (target_of_frame[f] >= 0)
      channel.values(static_cast<Eigen::Index>(f), target_of_frame[f]) = 1.0;
  return channel;
}

}  // namespace

bool AnimateOutput::certified() const {
  for (const AnimationReport& clip : clips)
    if (!clip.written.certified()) return false;
  return true;
}

AnimateOutput run_animate(const AnimateInput& input, const AnimateOptions& options,
                          Progress& progress) {
  const Stopwatch stopwatch;
  progress.start("animate");
  const std::vector<ChosenClip> clips = choose_clips(options.clips, input.avatar, options.fps);
  const AnimatedScene scene = read_animated_scene(input.written_files, input.written_meshes,
                                                  input.avatar, input.avatar_meshes);
  AnimateOutput output;
  const std::size_t garments = scene.garments.size();
  std::vector<GlbMorphTargets> targets(garments);
  std::vector<AnimationClip> written_clips;
  for (std::size_t g = 0; g < garments; ++g) targets[g].layout = &scene.garments[g].asset.gltf;
  // Each clip's targets, to key them per frame once every clip has its own.
  std::vector<std::vector<std::vector<int>>> target_of_frame;  // [clip][garment][frame]
  for (const ChosenClip& clip : clips) {
    AnimationReport report;
    report.skinned = check_clip(scene, clip, options.fps, nullptr, false);
    progress.log("animate", "{} (skinning alone)", clip_summary(report.skinned));
    const ClipCorrection correction = correct_clip(scene, clip, options.fps, report.skinned,
                                                   options.parameters, options.max_step, progress);
    report.steps = correction.steps;
    report.solves = correction.solves;
    report.push_iterations = correction.push_iterations;
    report.settle_iterations = correction.settle_iterations;
    report.push_seconds = correction.push_seconds;
    report.settle_seconds = correction.settle_seconds;
    report.solved_frames = correction.solved_frames;
    report.carried_frames = correction.carried_frames;
    report.corrections_failed = correction.corrections_failed;
    report.correction_seconds = correction.seconds;
    report.morph_targets = static_cast<int>(correction.targets.size());
    const std::size_t frames = correction.target_of_frame.size();
    std::vector<std::vector<int>> keyed(garments, std::vector<int>(frames, -1));
    for (std::size_t f = 0; f < frames; ++f) {
      const int t = correction.target_of_frame[f];
      if (t < 0) continue;
      ++report.corrected_frames;
      double sum = 0.0;
      Eigen::Index rows = 0;
      for (const MatrixX3d& offsets : correction.targets[static_cast<std::size_t>(t)]) {
        const Eigen::VectorXd lengths = offsets.rowwise().norm();
        sum += lengths.sum();
        rows += lengths.size();
        if (lengths.size() > 0) report.max_offset = std::max(report.max_offset, lengths.maxCoeff());
      }
      report.mean_offset += rows > 0 ? sum / static_cast<double>(rows) : 0.0;
      for (std::size_t g = 0; g < garments; ++g)
        keyed[g][f] = static_cast<int>(targets[g].deltas.size()) + t;
    }
    if (report.corrected_frames > 0) report.mean_offset /= report.corrected_frames;
    for (const std::vector<MatrixX3d>& target : correction.targets)
      for (std::size_t g = 0; g < garments; ++g) targets[g].deltas.push_back(target[g]);
    progress.log("animate",
                 "'{}': {} of {} frames corrected ({} solved, {} carried the last correction; {} "
                 "poses solved, {} failed) in {:.2f} s",
                 clip.clip.name, report.corrected_frames, frames, report.solved_frames,
                 report.carried_frames, report.solves, report.corrections_failed,
                 report.correction_seconds);
    if (!correction.first_failure.empty())
      progress.log("animate", "first failed correction: {}", correction.first_failure);
    target_of_frame.push_back(std::move(keyed));
    output.clips.push_back(std::move(report));
  }
  // Every written file gets the clips: the joint channels its skin plays (the garments of
  // one file share one skin) and, per garment with a corrected frame, its weights channel.
  std::map<std::string, std::vector<std::size_t>> garments_of_file;
  for (std::size_t g = 0; g < garments; ++g) garments_of_file[scene.garments[g].path].push_back(g);
  for (const auto& [path, members] : garments_of_file) {
    const SkinBinding& skin = *scene.garments[members.front()].asset.gltf.skin;
    std::vector<AnimationClip> file_clips;
    std::vector<GlbMorphTargets> file_targets;
    for (const std::size_t g : members) file_targets.push_back(targets[g]);
    for (std::size_t c = 0; c < clips.size(); ++c) {
      AnimationClip clip =
          bound_channels(clips[c].clip, bind_clip(skin, clips[c].clip, clips[c].translations));
      for (const std::size_t g : members)
        if (!targets[g].deltas.empty())
          clip.channels.push_back(frame_weights(
              scene.garments[g].asset.gltf.node_name, frame_times(clips[c].clip, options.fps),
              options.fps, target_of_frame[c][g], static_cast<int>(targets[g].deltas.size())));
      file_clips.push_back(std::move(clip));
    }
    add_glb_animation(path, file_targets, file_clips);
  }
  // The files as written, played again: the per-frame certificate.
  const AnimatedScene written = read_animated_scene(input.written_files, input.written_meshes,
                                                    input.avatar, input.avatar_meshes);
  for (std::size_t c = 0; c < clips.size(); ++c) {
    output.clips[c].written =
        check_clip(written, clips[c], options.fps, &output.clips[c].written_poses);
    progress.log("animate", "{} (as written)", clip_summary(output.clips[c].written));
  }
  output.seconds = stopwatch.seconds();
  return output;
}

nlohmann::ordered_json to_json(const AnimateOutput& output) {
  nlohmann::ordered_json clips = nlohmann::ordered_json::array();
  for (const AnimationReport& clip : output.clips) {
    nlohmann::ordered_json skinned = to_json(clip.skinned);
    skinned.erase("frames");
    const std::size_t frames = clip.written.frames.size();
    clips.push_back(
        {{"skinning_alone", skinned},
         {"corrected_frames", clip.corrected_frames},
         {"solved_frames", clip.solved_frames},
         {"carried_frames", clip.carried_frames},
         {"morph_targets", clip.morph_targets},
         {"poses_solved", clip.steps},
         {"corrections", clip.solves},
         {"corrections_failed", clip.corrections_failed},
         {"offset", {{"mean", clip.mean_offset}, {"max", clip.max_offset}}},
         {"push", {{"newton_iterations", clip.push_iterations}, {"seconds", clip.push_seconds}}},
         {"settle",
          {{"newton_iterations", clip.settle_iterations}, {"seconds", clip.settle_seconds}}},
         {"correction_seconds", clip.correction_seconds},
         {"seconds_per_frame",
          frames > 0 ? clip.correction_seconds / static_cast<double>(frames) : 0.0},
         {"written", to_json(clip.written)}});
  }
  return {{"certified", output.certified()}, {"seconds", output.seconds}, {"clips", clips}};
}

}  // namespace gr
