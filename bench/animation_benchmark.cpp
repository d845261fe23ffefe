// Animation: production garments retargeted onto an undressed body with --animation, played
// through the platform's idle clip and a second clip made here from the same rig ("reach":
// from the idle's first pose, the arms swing forward, one thigh steps forward and its knee
// bends, the spine turns). Per garment and clip: the frames skinning alone lets cross, the
// frames corrected, the frames that cross as written, the correction's cost per frame and
// the run's time. A Markdown table on stdout.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "bench/run_measures.hpp"
#include "core/common/stopwatch.hpp"
#include "core/io/gltf_document.hpp"
#include "core/skinning/skin_pose.hpp"
#include "retarget/retarget.hpp"

namespace fs = std::filesystem;

namespace {

constexpr double kPi = 3.14159265358979323846;

std::string shared(const std::string& relative) {
  return std::string(GR_SHARED_DATA_DIR) + "/" + relative;
}

struct Garment {
  std::string label;
  std::string file;
  std::string mesh;
};

std::vector<Garment> garments() {
  return {{"dress", shared("real/female-pose-standing.glb"), "Wolf3D_Outfit_Top.002"},
          {"jacket", shared("real/male-pose-standing.glb"), "Wolf3D_Outfit_Top.001"},
          {"shirt", shared("real/male-outfit.glb"), "Wolf3D_Outfit_Top"},
          {"trousers", shared("real/male-outfit.glb"), "Wolf3D_Outfit_Bottom"}};
}

Eigen::Quaterniond turn(const Eigen::Vector3d& axis, double degrees) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(degrees * kPi / 180.0, axis.normalized()));
}

using JointTurns = std::map<std::string, Eigen::Quaterniond>;

/// A key of a clip made from the rig: at `time`, world turns per joint (each applied to the
/// joint and, through it, to everything below).
struct PoseKey {
  double time = 0.0;
  JointTurns turns;
};

/// The turns of `key` blended with those of `next` by `s` (joints absent in one turn not).
JointTurns blend(const JointTurns& key, const JointTurns& next, double s) {
  JointTurns out;
  for (const auto& [name, q] : key) out[name] = q;
  for (const auto& [name, q] : next) out.emplace(name, Eigen::Quaterniond::Identity());
  for (auto& [name, q] : out) {
    const auto to = next.find(name);
    q = q.slerp(s, to == next.end() ? Eigen::Quaterniond::Identity() : to->second);
  }
  return out;
}

/// A clip from the idle clip's first pose through `keys` (the first at time 0), eased in and
/// out between keys, sampled every 0.05 s; the root held where the idle has it.
gr::AnimationClip made_clip(const gr::SkinBinding& skin, const gr::AnimationClip& idle,
                            const std::string& name, const std::vector<PoseKey>& keys) {
  const gr::ClipBinding binding = gr::bind_clip(skin, idle, gr::ClipTranslations::kRoots);
  const gr::SkeletonPose base = gr::clip_pose(skin, idle, binding, idle.start);
  const std::vector<Eigen::Matrix4d> base_worlds = gr::joint_worlds(skin, base);
  gr::AnimationClip clip;
  clip.name = name;
  clip.start = 0.0;
  clip.end = keys.back().time;
  std::vector<double> times;
  for (int k = 0; 0.05 * k <= clip.end + 1e-9; ++k) times.push_back(0.05 * k);
  std::vector<gr::AnimationChannel> channels(skin.joints.size());
  for (std::size_t j = 0; j < skin.joints.size(); ++j) {
    channels[j].node = skin.joints[j].name;
    channels[j].path = gr::ChannelPath::kRotation;
    channels[j].times = times;
    channels[j].values.resize(static_cast<Eigen::Index>(times.size()), 4);
  }
  for (std::size_t k = 0; k < times.size(); ++k) {
    std::size_t i = 0;
    while (i + 2 < keys.size() && keys[i + 1].time <= times[k]) ++i;
    const double span = keys[i + 1].time - keys[i].time;
    const double u = std::clamp((times[k] - keys[i].time) / span, 0.0, 1.0);
    const JointTurns turns = blend(keys[i].turns, keys[i + 1].turns, 0.5 - 0.5 * std::cos(kPi * u));
    // Each joint's world turn: its own times its parent's, from the root down.
    std::vector<Eigen::Quaterniond> world_turn(skin.joints.size(), Eigen::Quaterniond::Identity());
    std::vector<Eigen::Quaterniond> world(skin.joints.size());
    std::vector<bool> done(skin.joints.size(), false);
    const auto resolve = [&](auto&& self, std::size_t j) -> void {
      if (done[j]) return;
      const int parent = skin.joints[j].parent;
      Eigen::Quaterniond inherited = Eigen::Quaterniond::Identity();
      if (parent >= 0) {
        self(self, static_cast<std::size_t>(parent));
        inherited = world_turn[static_cast<std::size_t>(parent)];
      }
      const auto own = turns.find(skin.joints[j].name);
      world_turn[j] = own == turns.end() ? inherited : own->second * inherited;
      world[j] = world_turn[j] * Eigen::Quaterniond(base_worlds[j].topLeftCorner<3, 3>());
      done[j] = true;
    };
    for (std::size_t j = 0; j < skin.joints.size(); ++j) resolve(resolve, j);
    for (std::size_t j = 0; j < skin.joints.size(); ++j) {
      const int parent = skin.joints[j].parent;
      const Eigen::Quaterniond above =
          parent >= 0 ? world[static_cast<std::size_t>(parent)] : Eigen::Quaterniond::Identity();
      const Eigen::Quaterniond offset(skin.joints[j].parent_offset.topLeftCorner<3, 3>());
      const Eigen::Quaterniond local = ((above * offset).inverse() * world[j]).normalized();
      channels[j].values.row(static_cast<Eigen::Index>(k)) << local.x(), local.y(), local.z(),
          local.w();
    }
  }
  clip.channels = std::move(channels);
  for (const gr::AnimationChannel& c : idle.channels)
    if (c.node == "Hips" && c.path == gr::ChannelPath::kTranslation) {
      gr::AnimationChannel hips = c;
      hips.times = {0.0};
      hips.values = gr::sample_channel(c, idle.start).transpose();
      clip.channels.push_back(hips);
    }
  return clip;
}

/// The clips made from the rig (glTF: +Y up, +Z forward, +X the avatar's left):
/// - "reach", 2 s: the arms swing forward, one thigh steps forward with its knee bent, the
///   spine turns;
/// - "walk", 2 s: two strides, thighs swinging 30° each way, the back knee bent 50°, arms
///   swinging against the legs with elbows bent 40°;
/// - "guard", 1.6 s: both arms forward and elbows bent 110°, fists before the chest, a
///   crouch (thighs 40° forward, knees 70°), then back.
std::vector<gr::AnimationClip> made_clips(const gr::SkinBinding& skin,
                                          const gr::AnimationClip& idle) {
  const Eigen::Vector3d side = Eigen::Vector3d::UnitX();
  const auto at = [](double t, JointTurns turns) { return PoseKey{t, std::move(turns)}; };
  std::vector<gr::AnimationClip> clips;
  clips.push_back(
      made_clip(skin, idle, "reach",
                {at(0.0, {}), at(2.0, {{"LeftArm", turn(side, -70.0)},
                                       {"RightArm", turn(side, -50.0)},
                                       {"LeftForeArm", turn(side, -30.0)},
                                       {"LeftUpLeg", turn(side, -45.0)},
                                       {"LeftLeg", turn(side, 60.0)},
                                       {"Spine1", turn(Eigen::Vector3d::UnitY(), 20.0)}})}));
  const JointTurns left_stride = {
      {"LeftUpLeg", turn(side, -30.0)},    {"RightUpLeg", turn(side, 30.0)},
      {"RightLeg", turn(side, 50.0)},      {"RightArm", turn(side, -30.0)},
      {"RightForeArm", turn(side, -40.0)}, {"LeftArm", turn(side, 25.0)},
      {"LeftForeArm", turn(side, -20.0)}};
  JointTurns right_stride;
  for (const auto& [name, q] : left_stride) {
    std::string mirrored = name;
    if (name.rfind("Left", 0) == 0) mirrored = "Right" + name.substr(4);
    if (name.rfind("Right", 0) == 0) mirrored = "Left" + name.substr(5);
    right_stride[mirrored] = q;
  }
  clips.push_back(made_clip(skin, idle, "walk",
                            {at(0.0, {}), at(0.5, left_stride), at(1.0, right_stride),
                             at(1.5, left_stride), at(2.0, {})}));
  const JointTurns guard = {
      {"LeftArm", turn(side, -40.0)},      {"RightArm", turn(side, -40.0)},
      {"LeftForeArm", turn(side, -110.0)}, {"RightForeArm", turn(side, -110.0)},
      {"LeftUpLeg", turn(side, -40.0)},    {"RightUpLeg", turn(side, -40.0)},
      {"LeftLeg", turn(side, 70.0)},       {"RightLeg", turn(side, 70.0)}};
  clips.push_back(made_clip(skin, idle, "guard", {at(0.0, {}), at(0.8, guard), at(1.6, {})}));
  return clips;
}

/// Writes the clips made from the rig into `path` over a stand-in mesh skinned to the
/// avatar's joints.
void write_made_clips(const std::string& avatar, const std::string& idle_path,
                      const std::string& path) {
  const gr::GltfAsset body = gr::read_gltf_meshes(avatar, {"body.001"}, true);
  const gr::SkinBinding& skin = *body.gltf.skin;
  const std::vector<gr::AnimationClip> clips =
      made_clips(skin, gr::read_gltf_animations(idle_path).front());
  gr::ObjDocument stand_in;
  stand_in.positions = body.document.positions.topRows(3);
  stand_in.faces = {{gr::ObjCorner{0, -1, -1}, gr::ObjCorner{1, -1, -1}, gr::ObjCorner{2, -1, -1}}};
  gr::SkinBinding stand_in_skin = skin;
  stand_in_skin.weights = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(skin.joints.size()), 3);
  stand_in_skin.weights.row(0).setOnes();
  gr::write_glb_meshes(
      path, {gr::GlbMesh{"stand_in", &stand_in, nullptr, stand_in.positions, &stand_in_skin}},
      clips);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Animation: garments played through clips, corrected and certified per frame"};
  std::string quality_name = "balanced";
  int threads = 2;
  double fps = 30.0;
  std::vector<std::string> only;
  std::string out_dir = (fs::temp_directory_path() / "animation_benchmark").string();
  app.add_option("--quality", quality_name, "fast, balanced or accurate")->capture_default_str();
  app.add_option("--threads", threads, "Worker threads")->capture_default_str();
  app.add_option("--fps", fps, "Frames sampled per second")->capture_default_str();
  app.add_option("--garment", only, "Garments to run (default: all)");
  std::vector<std::string> only_clips;
  app.add_option("--clip", only_clips, "Clips to play: idle, reach, walk, guard (default: all)");
  app.add_option("--out", out_dir, "Folder for the runs' results")->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  const std::string avatar = shared("real/female-full-body.glb");
  const std::string idle = shared("real/female-idle.glb");
  fs::create_directories(out_dir);
  const std::string made = (fs::path(out_dir) / "made-clips.glb").string();
  write_made_clips(avatar, idle, made);
  std::vector<std::pair<std::string, std::string>> clips = {{"idle", idle}};
  for (const char* name : {"reach", "walk", "guard"}) clips.emplace_back(name, made + "#" + name);

  std::printf(
      "| garment | faces | clip | frames | crossing, skinning alone | corrected | solved | "
      "morph targets | failed | crossing as written | correction s/frame | run wall s | CPU s | "
      "result |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Garment& garment : garments()) {
    if (!only.empty() && std::find(only.begin(), only.end(), garment.label) == only.end()) continue;
    for (const auto& [clip_name, clip] : clips) {
      if (!only_clips.empty() &&
          std::find(only_clips.begin(), only_clips.end(), clip_name) == only_clips.end())
        continue;
      gr::RetargetOptions options;
      options.inputs.garment = garment.file;
      options.inputs.garment_mesh = garment.mesh;
      options.inputs.avatar = avatar;
      options.inputs.avatar_meshes = {"body.001"};
      options.quality = gr::parse_quality(quality_name);
      options.threads = threads;
      options.quiet = true;
      options.animations = {clip};
      options.fps = fps;
      options.out_dir = (fs::path(out_dir) / (garment.label + "_" + clip_name)).string();
      const double cpu_before = gr::bench::cpu_seconds();
      const gr::Stopwatch wall;
      gr::RetargetResult result;
      try {
        result = gr::run_retarget(options);
      } catch (const std::exception& e) {
        result.message = e.what();
      }
      const double cpu = gr::bench::cpu_seconds() - cpu_before;
      const gr::RetargetReport& r = result.report;
      if (!r.animation || r.animation->clips.empty()) {
        std::printf("| %s | %d | %s | - | - | - | - | - | - | - | - | %.1f | %.1f | %s: %s |\n",
                    garment.label.c_str(), r.normalize.garment_faces, clip_name.c_str(),
                    wall.seconds(), cpu, gr::to_string(result.status), result.message.c_str());
        continue;
      }
      const gr::AnimationReport& a = r.animation->clips.front();
      const double frames = static_cast<double>(a.written.frames.size());
      std::printf(
          "| %s | %d | %s | %zu | %zu | %d | %d | %d | %d | %zu | %.2f | %.1f | %.1f | %s |\n",
          garment.label.c_str(), r.normalize.garment_faces, clip_name.c_str(),
          a.written.frames.size(), a.skinned.crossing_frames(), a.corrected_frames, a.solved_frames,
          a.morph_targets, a.corrections_failed, a.written.crossing_frames(),
          a.correction_seconds / frames, wall.seconds(), cpu, gr::to_string(result.status));
      std::fflush(stdout);
    }
  }
  return 0;
}
