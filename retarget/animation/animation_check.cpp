#include "retarget/animation/animation_check.hpp"

#include <algorithm>
#include <map>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "core/common/errors.hpp"
#include "core/common/stopwatch.hpp"
#include "core/io/formats/mesh_formats.hpp"
#include "retarget/scene/normalization.hpp"
#include "validate/checks/mesh_intersections.hpp"
#include "validate/checks/self_intersections.hpp"

namespace gr {

namespace {

FacePair ordered(const FacePair& p) {
  return {std::min(p.first, p.second), std::max(p.first, p.second)};
}

std::vector<FacePair> sorted_pairs(std::vector<FacePair> pairs, bool order_each) {
  if (order_each)
    for (FacePair& p : pairs) p = ordered(p);
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

void read_part(const std::string& path, const std::vector<std::string>& meshes, bool whole_skin,
               const char* role, AnimatedScene::Part& part) {
  part.path = path;
  if (!mesh_format_for_path(path).skinned)
    throw InputError(path, 0,
                     fmt::format("the {} is not a glTF file: playing an animation needs skinned "
                                 "glTF garments and avatar",
                                 role));
  part.asset = whole_skin ? read_gltf_meshes(path, meshes, true)
                          : read_gltf(path, meshes.empty() ? std::string() : meshes.front());
  if (!part.asset.gltf.skin || part.asset.gltf.skin->weights.size() == 0)
    throw InputError(path, 0,
                     fmt::format("the {} has no skin: playing an animation needs skinned glTF "
                                 "garments and avatar",
                                 role));
  part.mesh = mesh_as_written(part.asset.document);
  try {
    part.skinned = prepare_skinned_mesh(*part.asset.gltf.skin, part.asset.document.positions);
  } catch (const std::invalid_argument& error) {
    throw InputError(path, 0, error.what());
  }
  part.morphs = read_morph_targets(part.asset.gltf, path, part.asset.document.positions.rows());
  if (!part.morphs.empty()) part.own_clips = read_gltf_animations(path);
}

/// The bind-space offsets the morph weights of `part`'s own clip named `clip` give at
/// `time`; false when none applies.
bool morph_offsets(const AnimatedScene::Part& part, const std::string& clip, double time,
                   MatrixX3d& offsets) {
  bool any = false;
  for (const AnimationClip& own : part.own_clips) {
    if (own.name != clip) continue;
    for (const AnimationChannel& channel : own.channels) {
      if (channel.path != ChannelPath::kWeights) continue;
      for (const MeshMorphTargets& targets : part.morphs) {
        if (targets.node != channel.node) continue;
        const Eigen::VectorXd weights = sample_channel(channel, time);
        for (Eigen::Index k = 0; k < weights.size(); ++k)
          if (weights(k) != 0.0 && static_cast<std::size_t>(k) < targets.deltas.size()) {
            if (!any) offsets = MatrixX3d::Zero(part.mesh.vertices.rows(), 3);
            offsets += weights(k) * targets.deltas[static_cast<std::size_t>(k)];
            any = true;
          }
      }
    }
  }
  return any;
}

TriangleMesh posed(const AnimatedScene::Part& part, const std::vector<Eigen::Matrix4d>& worlds,
                   const std::string& clip, double time) {
  MatrixX3d offsets;
  const bool morphed = morph_offsets(part, clip, time, offsets);
  return {
      pose_skinned_mesh(*part.asset.gltf.skin, part.skinned, worlds, morphed ? &offsets : nullptr),
      part.mesh.faces};
}

/// Per garment, its joints (garment joint, avatar joint) that share a name with an avatar
/// joint and lie within `tolerance` of it at rest.
std::vector<std::vector<std::pair<int, int>>> joints_at_rest_together(const AnimatedScene& scene,
                                                                      double tolerance) {
  const SkinBinding& avatar_skin = *scene.avatar.asset.gltf.skin;
  std::map<std::string, int> avatar_joint;
  for (std::size_t j = 0; j < avatar_skin.joints.size(); ++j)
    avatar_joint.emplace(avatar_skin.joints[j].name, static_cast<int>(j));
  std::vector<std::vector<std::pair<int, int>>> together(scene.garments.size());
  for (std::size_t g = 0; g < scene.garments.size(); ++g) {
    const SkinBinding& skin = *scene.garments[g].asset.gltf.skin;
    for (std::size_t j = 0; j < skin.joints.size(); ++j) {
      const auto match = avatar_joint.find(skin.joints[j].name);
      if (match == avatar_joint.end()) continue;
      const Eigen::Matrix4d& rest =
          avatar_skin.joints[static_cast<std::size_t>(match->second)].world;
      if ((skin.joints[j].world.col(3) - rest.col(3)).norm() <= tolerance)
        together[g].emplace_back(static_cast<int>(j), match->second);
    }
  }
  return together;
}

}  // namespace

AnimatedScene read_animated_scene(const std::vector<std::string>& garment_paths,
                                  const std::vector<std::string>& garment_meshes,
                                  const std::string& avatar_path,
                                  const std::vector<std::string>& avatar_meshes) {
  AnimatedScene scene;
  scene.garments.resize(garment_paths.size());
  for (std::size_t g = 0; g < garment_paths.size(); ++g) {
    const std::vector<std::string> mesh = g < garment_meshes.size() && !garment_meshes[g].empty()
                                              ? std::vector<std::string>{garment_meshes[g]}
                                              : std::vector<std::string>{};
    read_part(garment_paths[g], mesh, false, "garment", scene.garments[g]);
  }
  read_part(avatar_path, avatar_meshes, true, "avatar", scene.avatar);
  for (const AnimatedScene::Part& garment : scene.garments)
    scene.rest_self_pairs.push_back(
        sorted_pairs(find_self_intersecting_face_pairs(garment.mesh).pairs.pairs, true));
  scene.rest_avatar_self_pairs =
      sorted_pairs(find_self_intersecting_face_pairs(scene.avatar.mesh).pairs.pairs, true);
  for (std::size_t a = 0; a < scene.garments.size(); ++a)
    for (std::size_t b = a + 1; b < scene.garments.size(); ++b)
      scene.rest_layer_pairs.push_back(sorted_pairs(
          find_intersecting_face_pairs(scene.garments[a].mesh, scene.garments[b].mesh).pairs,
          false));
  return scene;
}

FrameFindings check_posed_frame(const AnimatedScene& scene,
                                const std::vector<TriangleMesh>& garments,
                                const TriangleMesh& avatar, double time) {
  FrameFindings frame;
  frame.time = time;
  frame.crossing_faces.resize(garments.size());
  const auto not_at_rest = [](const std::vector<FacePair>& pairs, const std::vector<FacePair>& rest,
                              bool order_each) {
    std::vector<FacePair> kept;
    for (const FacePair& p : pairs)
      if (!std::binary_search(rest.begin(), rest.end(), order_each ? ordered(p) : p))
        kept.push_back(p);
    return kept;
  };
  std::size_t pair = 0;
  for (std::size_t g = 0; g < garments.size(); ++g) {
    std::vector<int>& faces = frame.crossing_faces[g];
    const std::vector<FacePair> on_avatar = find_intersecting_face_pairs(garments[g], avatar).pairs;
    frame.avatar_pairs += on_avatar.size();
    for (const FacePair& p : on_avatar) faces.push_back(p.first);
    const std::vector<FacePair> self = not_at_rest(
        find_self_intersecting_face_pairs(garments[g]).pairs.pairs, scene.rest_self_pairs[g], true);
    frame.self_pairs += self.size();
    for (const FacePair& p : self) faces.insert(faces.end(), {p.first, p.second});
    for (std::size_t h = g + 1; h < garments.size(); ++h, ++pair) {
      const std::vector<FacePair> layer =
          not_at_rest(find_intersecting_face_pairs(garments[g], garments[h]).pairs,
                      scene.rest_layer_pairs[pair], false);
      frame.layer_pairs += layer.size();
      for (const FacePair& p : layer) {
        faces.push_back(p.first);
        frame.crossing_faces[h].push_back(p.second);
      }
    }
  }
  for (std::vector<int>& faces : frame.crossing_faces) {
    std::sort(faces.begin(), faces.end());
    faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  }
  return frame;
}

std::size_t ClipFindings::crossing_frames() const {
  return static_cast<std::size_t>(std::count_if(
      frames.begin(), frames.end(), [](const FrameFindings& f) { return f.total() > 0; }));
}

std::size_t ClipFindings::avatar_crossing_itself_frames() const {
  return static_cast<std::size_t>(std::count_if(
      frames.begin(), frames.end(),
      [](const FrameFindings& f) { return f.total() > 0 && f.avatar_self_pairs > 0; }));
}

std::optional<std::size_t> ClipFindings::first_crossing() const {
  for (std::size_t f = 0; f < frames.size(); ++f)
    if (frames[f].total() > 0) return f;
  return std::nullopt;
}

std::optional<std::size_t> ClipFindings::worst_frame() const {
  std::optional<std::size_t> worst;
  for (std::size_t f = 0; f < frames.size(); ++f)
    if (frames[f].total() > 0 && (!worst || frames[f].total() > frames[*worst].total())) worst = f;
  return worst;
}

ClipFindings check_clip(const AnimatedScene& scene, const ChosenClip& chosen, double fps,
                        ClipPoses* poses, bool explain) {
  const Stopwatch stopwatch;
  const AnimationClip& clip = chosen.clip;
  ClipFindings findings;
  findings.clip = clip.name;
  findings.file = clip.file;
  findings.fps = fps;
  findings.translations = chosen.translations;
  const SkinBinding& avatar_skin = *scene.avatar.asset.gltf.skin;
  const ClipBinding avatar_binding = bind_clip(avatar_skin, clip, chosen.translations);
  findings.avatar_driven_joints = avatar_binding.driven_joints;
  findings.unmatched_nodes = avatar_binding.unmatched_nodes;
  std::vector<ClipBinding> garment_bindings;
  for (const AnimatedScene::Part& garment : scene.garments) {
    garment_bindings.push_back(bind_clip(*garment.asset.gltf.skin, clip, chosen.translations));
    findings.garment_driven_joints.push_back(garment_bindings.back().driven_joints);
  }
  const std::vector<double> times = frame_times(clip, fps);
  findings.frames.resize(times.size());
  const double avatar_size = largest_side(scene.avatar.mesh.vertices);
  findings.drift_limit = kMaxJointDrift * avatar_size;
  const std::vector<std::vector<std::pair<int, int>>> same_joints =
      joints_at_rest_together(scene, kSameJointAtRest * avatar_size);
  std::vector<std::pair<double, int>> frame_drift(times.size(), {0.0, -1});
  if (poses) {
    poses->avatar.assign(times.size(), MatrixX3d());
    poses->garments.assign(times.size(), std::vector<MatrixX3d>());
  }
  tbb::parallel_for(std::size_t{0}, times.size(), [&](std::size_t f) {
    FrameFindings& frame = findings.frames[f];
    frame.time = times[f];
    const std::vector<Eigen::Matrix4d> avatar_worlds =
        posed_joint_worlds(avatar_skin, clip, avatar_binding, frame.time);
    const TriangleMesh avatar = posed(scene.avatar, avatar_worlds, clip.name, frame.time);
    std::vector<TriangleMesh> garments;
    for (std::size_t g = 0; g < scene.garments.size(); ++g) {
      const std::vector<Eigen::Matrix4d> worlds = posed_joint_worlds(
          *scene.garments[g].asset.gltf.skin, clip, garment_bindings[g], frame.time);
      for (const auto& [joint, avatar_joint] : same_joints[g]) {
        const double apart = (worlds[static_cast<std::size_t>(joint)].col(3) -
                              avatar_worlds[static_cast<std::size_t>(avatar_joint)].col(3))
                                 .norm();
        if (apart > frame_drift[f].first) frame_drift[f] = {apart, avatar_joint};
      }
      garments.push_back(posed(scene.garments[g], worlds, clip.name, frame.time));
    }
    frame = check_posed_frame(scene, garments, avatar, frame.time);
    if (explain && frame.total() > 0) {
      const std::vector<FacePair>& rest = scene.rest_avatar_self_pairs;
      for (const FacePair& p : find_self_intersecting_face_pairs(avatar).pairs.pairs)
        frame.avatar_self_pairs += !std::binary_search(rest.begin(), rest.end(), ordered(p));
    }
    if (poses) {
      poses->avatar[f] = avatar.vertices;
      for (const TriangleMesh& garment : garments) poses->garments[f].push_back(garment.vertices);
    }
  });
  for (std::size_t f = 0; f < times.size(); ++f)
    if (frame_drift[f].first > findings.joint_drift) {
      findings.joint_drift = frame_drift[f].first;
      findings.drift_joint =
          avatar_skin.joints[static_cast<std::size_t>(frame_drift[f].second)].name;
      findings.drift_frame = f;
    }
  findings.seconds = stopwatch.seconds();
  return findings;
}

nlohmann::ordered_json to_json(const ClipFindings& findings) {
  const auto frame_json = [&](std::optional<std::size_t> f) -> nlohmann::ordered_json {
    if (!f) return nullptr;
    const FrameFindings& frame = findings.frames[*f];
    return {{"index", *f}, {"time", frame.time}, {"pairs", frame.total()}};
  };
  nlohmann::ordered_json frames = nlohmann::ordered_json::array();
  for (const FrameFindings& frame : findings.frames)
    frames.push_back({{"time", frame.time},
                      {"avatar_pairs", frame.avatar_pairs},
                      {"self_pairs", frame.self_pairs},
                      {"layer_pairs", frame.layer_pairs},
                      {"avatar_self_pairs", frame.avatar_self_pairs}});
  return {{"clip", findings.clip},
          {"file", findings.file},
          {"fps", findings.fps},
          {"translations", findings.translations == ClipTranslations::kAll ? "all" : "roots"},
          {"avatar_driven_joints", findings.avatar_driven_joints},
          {"garment_driven_joints", findings.garment_driven_joints},
          {"unmatched_nodes", findings.unmatched_nodes},
          {"frame_count", findings.frames.size()},
          {"crossing_frames", findings.crossing_frames()},
          {"joint_drift",
           {{"largest", findings.joint_drift},
            {"joint", findings.drift_joint},
            {"frame", findings.drift_frame},
            {"limit", findings.drift_limit},
            {"meaning",
             "how far a garment joint moves from the avatar joint of its name, among those "
             "together at rest (file units); beyond the limit the two rigs are placed "
             "otherwise, and the frames checked are not those an engine plays"}}},
          {"certified", findings.certified()},
          {"avatar_crossing_itself_frames", findings.avatar_crossing_itself_frames()},
          {"first_crossing_frame", frame_json(findings.first_crossing())},
          {"worst_frame", frame_json(findings.worst_frame())},
          {"seconds", findings.seconds},
          {"frames", frames}};
}

std::string clip_summary(const ClipFindings& findings) {
  std::string line =
      fmt::format("animation '{}': {} frames at {:g} fps, {} crossing", findings.clip,
                  findings.frames.size(), findings.fps, findings.crossing_frames());
  if (const auto first = findings.first_crossing()) {
    const auto worst = *findings.worst_frame();
    line += fmt::format(" (first: frame {} at {:.3f} s; worst: frame {} at {:.3f} s, {} pairs)",
                        *first, findings.frames[*first].time, worst, findings.frames[worst].time,
                        findings.frames[worst].total());
    if (const std::size_t own = findings.avatar_crossing_itself_frames(); own > 0)
      line += fmt::format("; in {} of them the avatar crosses itself", own);
  }
  if (!findings.rigs_agree())
    line += fmt::format(
        "; NOT certified: the garment's joint '{}' moves {:.3g} from the avatar's in frame {} "
        "(together at rest): the two files place the rig otherwise (an armature?)",
        findings.drift_joint, findings.joint_drift, findings.drift_frame);
  return line;
}

}  // namespace gr
