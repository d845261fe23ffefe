#pragma once

#include <string>
#include <vector>

#include "core/io/gltf_animation.hpp"
#include "core/skinning/skin_pose.hpp"

namespace gr {

/// A clip to play, and which of its translations the skins take.
struct ChosenClip {
  AnimationClip clip;
  /// kAll for a clip from the avatar's own file, kRoots for one from another file of the
  /// same rig (see ClipTranslations).
  ClipTranslations translations = ClipTranslations::kAll;
};

/// Frames a clip may be sampled in: a clip of ten minutes at 120 fps, far beyond the
/// platforms' clips, and a bound on the memory the frames take.
constexpr double kMaxClipFrames = 100000.0;

/// The clips `specs` name, in order. A spec is `all` (every clip of the avatar's file), the
/// name of a clip of the avatar's file, a glTF file (every clip in it), or `FILE#NAME` (the
/// clip of that file so named). A clip named twice is played once.
/// @throw InputError naming the file for a file that cannot be read, a clip name it does not
///        have (the message lists the names), a file with no animation, or a clip that `fps`
///        would sample in more than kMaxClipFrames frames.
std::vector<ChosenClip> choose_clips(const std::vector<std::string>& specs,
                                     const std::string& avatar_path, double fps);

}  // namespace gr
