#include "core/io/gltf_animation.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/common/errors.hpp"
#include "core/io/gltf_accessors.hpp"
#include "core/io/gltf_document.hpp"
#include "core/io/gltf_model.hpp"

namespace gr {

namespace {

ChannelPath channel_path(const std::string& name, const std::string& path,
                         const std::string& clip) {
  if (name == "translation") return ChannelPath::kTranslation;
  if (name == "rotation") return ChannelPath::kRotation;
  if (name == "scale") return ChannelPath::kScale;
  if (name == "weights") return ChannelPath::kWeights;
  throw InputError(
      path, 0, fmt::format("animation '{}' drives '{}', which is not a node property", clip, name));
}

KeyInterpolation key_interpolation(const std::string& name) {
  if (name == "STEP") return KeyInterpolation::kStep;
  if (name == "CUBICSPLINE") return KeyInterpolation::kCubicSpline;
  return KeyInterpolation::kLinear;  // glTF's default, also when the field is absent
}

/// Components per value: 3, 4, or the morph target count of the node's mesh.
int component_count(const tinygltf::Model& model, const tinygltf::Node& node, ChannelPath path,
                    const std::string& file, const std::string& clip) {
  if (path == ChannelPath::kTranslation || path == ChannelPath::kScale) return 3;
  if (path == ChannelPath::kRotation) return 4;
  const int targets =
      node.mesh >= 0 && static_cast<std::size_t>(node.mesh) < model.meshes.size() &&
              !model.meshes[static_cast<std::size_t>(node.mesh)].primitives.empty()
          ? static_cast<int>(
                model.meshes[static_cast<std::size_t>(node.mesh)].primitives.front().targets.size())
          : 0;
  if (targets == 0)
    throw InputError(file, 0,
                     fmt::format("animation '{}' drives the morph weights of node '{}', which "
                                 "has no morph target",
                                 clip, node.name));
  return targets;
}

AnimationChannel read_channel(const tinygltf::Model& model, const tinygltf::Animation& animation,
                              const tinygltf::AnimationChannel& source, const std::string& file,
                              const std::string& clip) {
  if (source.sampler < 0 || static_cast<std::size_t>(source.sampler) >= animation.samplers.size())
    throw InputError(
        file, 0,
        fmt::format("animation '{}' has a channel with no sampler {}", clip, source.sampler));
  if (source.target_node < 0 || static_cast<std::size_t>(source.target_node) >= model.nodes.size())
    throw InputError(file, 0,
                     fmt::format("animation '{}' has a channel on node {}, which does not exist",
                                 clip, source.target_node));
  const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(source.target_node)];
  const tinygltf::AnimationSampler& sampler =
      animation.samplers[static_cast<std::size_t>(source.sampler)];
  AnimationChannel channel;
  channel.node = node.name.empty() ? fmt::format("node_{}", source.target_node) : node.name;
  channel.path = channel_path(source.target_path, file, clip);
  channel.interpolation = key_interpolation(sampler.interpolation);
  const std::string what = fmt::format("animation '{}' channel on '{}'", clip, channel.node);
  const std::size_t keys = accessor_count(model, sampler.input, file);
  channel.times = read_accessor(model, sampler.input, TINYGLTF_TYPE_SCALAR, keys, file,
                                (what + " times").c_str());
  if (keys == 0) throw InputError(file, 0, what + " has no keyframe");
  for (std::size_t k = 0; k < keys; ++k)
    if (!std::isfinite(channel.times[k]) || (k > 0 && !(channel.times[k] > channel.times[k - 1])))
      throw InputError(file, 0,
                       fmt::format("{}: keyframe times are not finite and strictly increasing "
                                   "(key {})",
                                   what, k));
  const int components = component_count(model, node, channel.path, file, clip);
  const std::size_t rows = keys * (channel.interpolation == KeyInterpolation::kCubicSpline ? 3 : 1);
  const std::size_t count = accessor_count(model, sampler.output, file);
  const int type = channel.path == ChannelPath::kWeights ? TINYGLTF_TYPE_SCALAR
                   : components == 4                     ? TINYGLTF_TYPE_VEC4
                                                         : TINYGLTF_TYPE_VEC3;
  const std::size_t elements =
      channel.path == ChannelPath::kWeights ? rows * static_cast<std::size_t>(components) : rows;
  if (count != elements)
    throw InputError(
        file, 0,
        fmt::format("{}: {} values for {} keyframes (expected {})", what, count, keys, elements));
  const std::vector<double> values =
      read_accessor(model, sampler.output, type, elements, file, (what + " values").c_str());
  channel.values.resize(static_cast<Eigen::Index>(rows), components);
  for (std::size_t r = 0; r < rows; ++r)
    for (int c = 0; c < components; ++c) {
      const double value =
          values[r * static_cast<std::size_t>(components) + static_cast<std::size_t>(c)];
      if (!std::isfinite(value))
        throw InputError(file, 0, fmt::format("{}: value {} is not finite", what, r));
      channel.values(static_cast<Eigen::Index>(r), c) = value;
    }
  return channel;
}

/// Row of keyframe `k`'s value (cubic splines store in-tangent, value, out-tangent).
Eigen::Index value_row(const AnimationChannel& channel, std::size_t k) {
  const auto key = static_cast<Eigen::Index>(k);
  return channel.interpolation == KeyInterpolation::kCubicSpline ? 3 * key + 1 : key;
}

Eigen::Quaterniond quaternion(const Eigen::VectorXd& xyzw) {
  return Eigen::Quaterniond(xyzw(3), xyzw(0), xyzw(1), xyzw(2));
}

}  // namespace

std::vector<AnimationClip> read_gltf_animations(const std::string& path) {
  const tinygltf::Model model = load_gltf_model(path);
  std::vector<AnimationClip> clips;
  for (std::size_t a = 0; a < model.animations.size(); ++a) {
    const tinygltf::Animation& animation = model.animations[a];
    AnimationClip clip;
    clip.name = animation.name.empty() ? fmt::format("animation_{}", a) : animation.name;
    clip.file = path;
    for (const tinygltf::AnimationChannel& source : animation.channels)
      clip.channels.push_back(read_channel(model, animation, source, path, clip.name));
    bool first = true;
    for (const AnimationChannel& channel : clip.channels) {
      clip.start = first ? channel.times.front() : std::min(clip.start, channel.times.front());
      clip.end = first ? channel.times.back() : std::max(clip.end, channel.times.back());
      first = false;
    }
    clips.push_back(std::move(clip));
  }
  return clips;
}

std::vector<MeshMorphTargets> read_morph_targets(const GltfDocument& gltf, const std::string& path,
                                                 Eigen::Index position_count) {
  const tinygltf::Model& model = gltf.model->model;
  std::vector<MeshMorphTargets> result;
  std::vector<int> mesh_of_entry;
  for (const GltfPrimitive& part : gltf.primitives) {
    const tinygltf::Primitive& primitive = model.meshes[static_cast<std::size_t>(part.mesh)]
                                               .primitives[static_cast<std::size_t>(part.source)];
    if (primitive.targets.empty()) continue;
    auto entry = std::find(mesh_of_entry.begin(), mesh_of_entry.end(), part.mesh);
    if (entry == mesh_of_entry.end()) {
      MeshMorphTargets targets;
      for (std::size_t n = 0; n < model.nodes.size() && targets.node.empty(); ++n)
        if (model.nodes[n].mesh == part.mesh)
          targets.node =
              model.nodes[n].name.empty() ? fmt::format("node_{}", n) : model.nodes[n].name;
      result.push_back(std::move(targets));
      mesh_of_entry.push_back(part.mesh);
      entry = mesh_of_entry.end() - 1;
    }
    MeshMorphTargets& targets = result[static_cast<std::size_t>(entry - mesh_of_entry.begin())];
    if (targets.deltas.size() < primitive.targets.size())
      targets.deltas.resize(primitive.targets.size(), MatrixX3d::Zero(position_count, 3));
    for (std::size_t t = 0; t < primitive.targets.size(); ++t) {
      const auto it = primitive.targets[t].find("POSITION");
      if (it == primitive.targets[t].end()) continue;
      const std::vector<double> xyz = read_accessor(model, it->second, TINYGLTF_TYPE_VEC3,
                                                    static_cast<std::size_t>(part.position_count),
                                                    path, "morph target POSITION");
      for (int v = 0; v < part.position_count; ++v)
        for (int c = 0; c < 3; ++c)
          targets.deltas[t](part.first_position + v, c) =
              xyz[3 * static_cast<std::size_t>(v) + static_cast<std::size_t>(c)];
    }
  }
  return result;
}

Eigen::VectorXd sample_channel(const AnimationChannel& channel, double time) {
  const std::vector<double>& times = channel.times;
  const bool rotation = channel.path == ChannelPath::kRotation;
  const auto finish = [&](Eigen::VectorXd value) {
    if (rotation) value.normalize();
    return value;
  };
  if (time <= times.front()) return finish(channel.values.row(value_row(channel, 0)).transpose());
  if (time >= times.back())
    return finish(channel.values.row(value_row(channel, times.size() - 1)).transpose());
  const auto after =
      static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), time) - times.begin());
  const std::size_t before = after - 1;
  const Eigen::VectorXd v0 = channel.values.row(value_row(channel, before)).transpose();
  const Eigen::VectorXd v1 = channel.values.row(value_row(channel, after)).transpose();
  const double span = times[after] - times[before];
  const double s = (time - times[before]) / span;
  switch (channel.interpolation) {
    case KeyInterpolation::kStep: return finish(v0);
    case KeyInterpolation::kLinear:
      if (rotation) {
        const Eigen::Quaterniond q =
            quaternion(v0).normalized().slerp(s, quaternion(v1).normalized());
        return Eigen::Vector4d(q.x(), q.y(), q.z(), q.w());
      }
      return (1.0 - s) * v0 + s * v1;
    case KeyInterpolation::kCubicSpline: {
      const Eigen::VectorXd out0 = channel.values.row(value_row(channel, before) + 1).transpose();
      const Eigen::VectorXd in1 = channel.values.row(value_row(channel, after) - 1).transpose();
      const double s2 = s * s;
      const double s3 = s2 * s;
      return finish((2 * s3 - 3 * s2 + 1) * v0 + (s3 - 2 * s2 + s) * span * out0 +
                    (-2 * s3 + 3 * s2) * v1 + (s3 - s2) * span * in1);
    }
  }
  return finish(v0);
}

}  // namespace gr
