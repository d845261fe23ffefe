#pragma once

#include <string>
#include <vector>

#include "core/common/types.hpp"

namespace gr {

struct GltfDocument;

/// What an animation channel drives on its node.
enum class ChannelPath { kTranslation, kRotation, kScale, kWeights };

/// How a channel's value runs between its keyframes (glTF 2.0 sampler interpolation).
enum class KeyInterpolation { kStep, kLinear, kCubicSpline };

/// One channel of a glTF animation: a node's translation, rotation, scale or morph weights
/// over time.
struct AnimationChannel {
  std::string node;  ///< the target node's name; `node_<i>` when it has none
  ChannelPath path = ChannelPath::kRotation;
  KeyInterpolation interpolation = KeyInterpolation::kLinear;
  std::vector<double> times;  ///< keyframe times in seconds, strictly increasing
  /// One row per keyframe (cubic spline: three rows per keyframe, in-tangent, value,
  /// out-tangent); 3 columns for translation and scale, 4 (x, y, z, w) for rotation, one
  /// per morph target for weights.
  Eigen::MatrixXd values;
};

/// A glTF animation: its channels and the time span they cover.
struct AnimationClip {
  std::string name;  ///< as the file names it; `animation_<i>` when it has none
  std::string file;  ///< the file it was read from
  std::vector<AnimationChannel> channels;
  double start = 0.0;  ///< the earliest keyframe of any channel
  double end = 0.0;    ///< the latest
};

/// Reads every animation of a glTF file (GLB or JSON), in file order.
/// @throw InputError naming `path` for a file that cannot be parsed, a channel whose
///        sampler, node or accessors do not exist or do not match (a count of values that
///        is not keyframes × components, a weights channel on a node without morph
///        targets), keyframe times that are not finite and strictly increasing, or a value
///        that is not finite.
std::vector<AnimationClip> read_gltf_animations(const std::string& path);

/// The value of `channel` at `time` (seconds), as glTF defines its interpolation: the first
/// value before the first keyframe, the last after the last; rotations are interpolated by
/// spherical linear interpolation and returned normalized.
Eigen::VectorXd sample_channel(const AnimationChannel& channel, double time);

/// The morph targets of one glTF mesh of a read document.
struct MeshMorphTargets {
  std::string node;  ///< the first node placing the mesh: the node weights channels name
  /// Per target, its position deltas over the whole document (#P×3, in the skin's bind
  /// space, zero outside the mesh's primitives).
  std::vector<MatrixX3d> deltas;
};

/// The POSITION morph targets of every mesh of `gltf` that has some, read from its model.
/// @throw InputError naming `path` for a target accessor that cannot be read (missing, of
///        the wrong type or count, or sparse).
std::vector<MeshMorphTargets> read_morph_targets(const GltfDocument& gltf, const std::string& path,
                                                 Eigen::Index position_count);

}  // namespace gr
