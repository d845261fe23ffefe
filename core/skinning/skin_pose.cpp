#include "core/skinning/skin_pose.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

namespace gr {

namespace {

Eigen::Matrix4d trs_matrix(const Eigen::Vector3d& translation, const Eigen::Quaterniond& rotation,
                           const Eigen::Vector3d& scale) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = rotation.normalized().toRotationMatrix() * scale.asDiagonal();
  m.topRightCorner<3, 1>() = translation;
  return m;
}

/// sum_j w_j world_j inverse_bind_j for one vertex, weights normalized; false when the
/// vertex has no weight.
bool blend_matrix(const SkinBinding& skin, const std::vector<Eigen::Matrix4d>& worlds,
                  Eigen::Index vertex, Eigen::Matrix4d& blend) {
  // Summed in joint order, as the reader sums them, so copies of a seam vertex stay equal.
  double total = 0.0;
  for (Eigen::Index j = 0; j < skin.weights.rows(); ++j) total += skin.weights(j, vertex);
  if (!(total > 0.0)) return false;
  blend.setZero();
  for (Eigen::Index j = 0; j < skin.weights.rows(); ++j)
    if (const double w = skin.weights(j, vertex); w != 0.0)
      blend += (w / total) * worlds[static_cast<std::size_t>(j)] *
               skin.joints[static_cast<std::size_t>(j)].inverse_bind;
  return true;
}

}  // namespace

ClipBinding bind_clip(const SkinBinding& skin, const AnimationClip& clip,
                      ClipTranslations translations) {
  std::unordered_map<std::string, int> joint_of_name;
  for (std::size_t j = 0; j < skin.joints.size(); ++j)
    joint_of_name.emplace(skin.joints[j].name, static_cast<int>(j));
  ClipBinding binding;
  binding.channels.assign(skin.joints.size(), {-1, -1, -1});
  for (std::size_t c = 0; c < clip.channels.size(); ++c) {
    const AnimationChannel& channel = clip.channels[c];
    if (channel.path == ChannelPath::kWeights) continue;
    const auto found = joint_of_name.find(channel.node);
    if (found == joint_of_name.end()) {
      if (std::find(binding.unmatched_nodes.begin(), binding.unmatched_nodes.end(), channel.node) ==
          binding.unmatched_nodes.end())
        binding.unmatched_nodes.push_back(channel.node);
      continue;
    }
    const auto joint = static_cast<std::size_t>(found->second);
    if (channel.path == ChannelPath::kTranslation && translations == ClipTranslations::kRoots &&
        skin.joints[joint].parent >= 0)
      continue;
    const int slot = channel.path == ChannelPath::kTranslation ? 0
                     : channel.path == ChannelPath::kRotation  ? 1
                                                               : 2;
    binding.channels[joint][static_cast<std::size_t>(slot)] = static_cast<int>(c);
  }
  for (const auto& slots : binding.channels)
    if (slots[0] >= 0 || slots[1] >= 0 || slots[2] >= 0) ++binding.driven_joints;
  return binding;
}

SkeletonPose rest_pose(const SkinBinding& skin) {
  SkeletonPose pose;
  for (const SkinJoint& joint : skin.joints)
    pose.push_back({joint.translation, joint.rotation, joint.scale});
  return pose;
}

SkeletonPose clip_pose(const SkinBinding& skin, const AnimationClip& clip,
                       const ClipBinding& binding, double time) {
  SkeletonPose pose = rest_pose(skin);
  for (std::size_t j = 0; j < pose.size(); ++j) {
    const auto& slots = binding.channels[j];
    const auto sample = [&](int slot) {
      return sample_channel(clip.channels[static_cast<std::size_t>(slot)], time);
    };
    if (slots[0] >= 0) pose[j].translation = sample(slots[0]);
    if (slots[1] >= 0) {
      const Eigen::VectorXd q = sample(slots[1]);
      pose[j].rotation = Eigen::Quaterniond(q(3), q(0), q(1), q(2));
    }
    if (slots[2] >= 0) pose[j].scale = sample(slots[2]);
  }
  return pose;
}

SkeletonPose blend_poses(const SkeletonPose& from, const SkeletonPose& to, double s) {
  SkeletonPose pose(from.size());
  for (std::size_t j = 0; j < from.size(); ++j) {
    pose[j].translation = (1.0 - s) * from[j].translation + s * to[j].translation;
    pose[j].rotation = from[j].rotation.normalized().slerp(s, to[j].rotation.normalized());
    pose[j].scale = (1.0 - s) * from[j].scale + s * to[j].scale;
  }
  return pose;
}

std::vector<Eigen::Matrix4d> joint_worlds(const SkinBinding& skin, const SkeletonPose& pose) {
  const std::size_t count = skin.joints.size();
  std::vector<Eigen::Matrix4d> local(count);
  for (std::size_t j = 0; j < count; ++j)
    local[j] = skin.joints[j].parent_offset *
               trs_matrix(pose[j].translation, pose[j].rotation, pose[j].scale);
  // Parents may follow their children in a skin's joint list: resolve each chain once.
  std::vector<Eigen::Matrix4d> world(count);
  std::vector<bool> done(count, false);
  std::vector<std::size_t> chain;
  for (std::size_t j = 0; j < count; ++j) {
    chain.clear();
    for (auto k = static_cast<int>(j); k >= 0 && !done[static_cast<std::size_t>(k)];
         k = skin.joints[static_cast<std::size_t>(k)].parent)
      chain.push_back(static_cast<std::size_t>(k));
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      const int parent = skin.joints[*it].parent;
      world[*it] = parent >= 0
                       ? Eigen::Matrix4d(world[static_cast<std::size_t>(parent)] * local[*it])
                       : local[*it];
      done[*it] = true;
    }
  }
  return world;
}

std::vector<Eigen::Matrix4d> posed_joint_worlds(const SkinBinding& skin, const AnimationClip& clip,
                                                const ClipBinding& binding, double time) {
  return joint_worlds(skin, clip_pose(skin, clip, binding, time));
}

double frame_count(const AnimationClip& clip, double fps) {
  // A frame at the end itself is kept even when rounding puts it a hair beyond: keyframe
  // times are 32-bit floats in a file.
  return std::floor((clip.end - clip.start) * fps + 1e-3) + 1.0;
}

std::vector<double> frame_times(const AnimationClip& clip, double fps) {
  std::vector<double> times;
  const auto count = static_cast<long>(frame_count(clip, fps));
  for (long k = 0; k < count; ++k) times.push_back(clip.start + static_cast<double>(k) / fps);
  return times;
}

SkinnedMesh prepare_skinned_mesh(const SkinBinding& skin,
                                 const Eigen::Ref<const MatrixX3d>& rest_positions) {
  std::vector<Eigen::Matrix4d> rest(skin.joints.size());
  for (std::size_t j = 0; j < skin.joints.size(); ++j) rest[j] = skin.joints[j].world;
  SkinnedMesh mesh;
  mesh.bind_positions = rest_positions;
  mesh.weighted.assign(static_cast<std::size_t>(rest_positions.rows()), false);
  Eigen::Matrix4d blend;
  for (Eigen::Index v = 0; v < rest_positions.rows(); ++v) {
    if (!blend_matrix(skin, rest, v, blend)) continue;
    const Eigen::FullPivLU<Eigen::Matrix3d> lu(blend.topLeftCorner<3, 3>());
    if (!lu.isInvertible())
      throw std::invalid_argument("skinned vertex " + std::to_string(v) +
                                  " has a singular rest blend matrix");
    mesh.bind_positions.row(v) =
        lu.solve(rest_positions.row(v).transpose() - blend.topRightCorner<3, 1>()).transpose();
    mesh.weighted[static_cast<std::size_t>(v)] = true;
  }
  return mesh;
}

MatrixX3d pose_skinned_mesh(const SkinBinding& skin, const SkinnedMesh& mesh,
                            const std::vector<Eigen::Matrix4d>& worlds,
                            const MatrixX3d* bind_offsets) {
  MatrixX3d posed = mesh.bind_positions;
  if (bind_offsets) posed += *bind_offsets;
  Eigen::Matrix4d blend;
  for (Eigen::Index v = 0; v < posed.rows(); ++v)
    if (mesh.weighted[static_cast<std::size_t>(v)] && blend_matrix(skin, worlds, v, blend))
      posed.row(v) =
          (blend.topLeftCorner<3, 3>() * posed.row(v).transpose() + blend.topRightCorner<3, 1>())
              .transpose();
  return posed;
}

std::vector<Eigen::Matrix3d> blend_linear_parts(const SkinBinding& skin, const SkinnedMesh& mesh,
                                                const std::vector<Eigen::Matrix4d>& worlds) {
  std::vector<Eigen::Matrix3d> parts(static_cast<std::size_t>(mesh.bind_positions.rows()),
                                     Eigen::Matrix3d::Identity());
  Eigen::Matrix4d blend;
  for (Eigen::Index v = 0; v < mesh.bind_positions.rows(); ++v)
    if (mesh.weighted[static_cast<std::size_t>(v)] && blend_matrix(skin, worlds, v, blend))
      parts[static_cast<std::size_t>(v)] = blend.topLeftCorner<3, 3>();
  return parts;
}

}  // namespace gr
