#include "retarget/animation/animation_clips.hpp"

#include <algorithm>
#include <filesystem>
#include <map>

#include <fmt/format.h>

#include "core/common/errors.hpp"
#include "core/io/formats/mesh_formats.hpp"

namespace gr {

namespace {

namespace fs = std::filesystem;

/// Files of a format that carries skins are the ones that can hold animations.
bool is_rig_file(const std::string& path) { return mesh_format_for_path(path).skinned; }

bool same_file(const std::string& a, const std::string& b) {
  std::error_code error;
  return fs::equivalent(a, b, error);
}

std::vector<AnimationClip> clips_of(const std::string& path) {
  std::vector<AnimationClip> clips = read_gltf_animations(path);
  if (clips.empty()) throw InputError(path, 0, "has no animation");
  return clips;
}

}  // namespace

std::vector<ChosenClip> choose_clips(const std::vector<std::string>& specs,
                                     const std::string& avatar_path, double fps) {
  std::map<std::string, std::vector<AnimationClip>> files;
  const auto clips_in = [&](const std::string& path) -> const std::vector<AnimationClip>& {
    auto it = files.find(path);
    if (it == files.end()) it = files.emplace(path, clips_of(path)).first;
    return it->second;
  };
  std::vector<ChosenClip> chosen;
  const auto add = [&](const AnimationClip& clip) {
    for (const ChosenClip& c : chosen)
      if (c.clip.file == clip.file && c.clip.name == clip.name) return;
    if (const double frames = frame_count(clip, fps); !(frames <= kMaxClipFrames))
      throw InputError(clip.file, 0,
                       fmt::format("animation '{}' ({:.3g} s) sampled at {:g} fps takes {:.3g} "
                                   "frames, more than {:g}: lower --fps",
                                   clip.name, clip.end - clip.start, fps, frames, kMaxClipFrames));
    const bool own = clip.file == avatar_path || same_file(clip.file, avatar_path);
    chosen.push_back({clip, own ? ClipTranslations::kAll : ClipTranslations::kRoots});
  };
  for (const std::string& spec : specs) {
    std::string file = avatar_path;
    std::string name = spec;
    if (const auto hash = spec.rfind('#');
        hash != std::string::npos && hash > 0 && is_rig_file(spec.substr(0, hash))) {
      file = spec.substr(0, hash);
      name = spec.substr(hash + 1);
    } else if (is_rig_file(spec)) {
      file = spec;
      name = "all";
    }
    if (!is_rig_file(file))
      throw InputError(
          file, 0, fmt::format("--animation '{}' needs a glTF avatar or a glTF clip file", spec));
    const std::vector<AnimationClip>& clips = clips_in(file);
    if (name == "all") {
      for (const AnimationClip& clip : clips) add(clip);
      continue;
    }
    const auto found = std::find_if(clips.begin(), clips.end(),
                                    [&](const AnimationClip& c) { return c.name == name; });
    if (found == clips.end()) {
      std::vector<std::string> names;
      for (const AnimationClip& clip : clips) names.push_back("'" + clip.name + "'");
      throw InputError(file, 0,
                       fmt::format("has no animation named '{}' (animations: {})", name,
                                   fmt::join(names, ", ")));
    }
    add(*found);
  }
  return chosen;
}

}  // namespace gr
