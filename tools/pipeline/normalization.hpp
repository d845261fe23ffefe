#pragma once

#include <optional>

#include "core/common/types.hpp"
#include "tools/pipeline/scene.hpp"

namespace gr {

/// x ↦ scale · R · (x − center): a change of units, axes and origin.
struct Similarity {
  double scale = 1.0;
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Vector3d center = Vector3d::Zero();

  Vector3d apply(const Vector3d& x) const { return scale * (rotation * (x - center)); }
  Vector3d invert(const Vector3d& y) const { return rotation.transpose() * y / scale + center; }
  /// Each row of `points` (#P×3) mapped.
  MatrixX3d apply_rows(const Eigen::Ref<const MatrixX3d>& points) const;
  MatrixX3d invert_rows(const Eigen::Ref<const MatrixX3d>& points) const;
};

/// Where each file's frame lands in the normalized scene, where the body is about
/// kNormalizedHeight units tall and every parameter (dhat, voxel size) is expressed.
struct Normalization {
  Similarity garment_to_scene;  ///< garment (and source skeleton) file frame → scene
  Similarity avatar_to_scene;   ///< avatar (and target skeleton) file frame → scene
};

constexpr double kNormalizedHeight = 2.0;

/// With skeletons: the source skeleton's largest bounding-box side becomes 2 and its box
/// centre the origin; the target skeleton is scaled to the same size, centred on it, and
/// turned by the signed axis permutation that best aligns its joints with the source's
/// (so a Y-up avatar meets a Z-up garment). Without: garment and avatar share one frame,
/// scaled so the avatar's largest bounding-box side is 2 and centred on its box.
/// @throw InputError when a skeleton or the avatar has zero extent.
Normalization normalize_scene(const Scene& scene);

/// A scene's meshes and skeletons in normalized scene units.
struct NormalizedScene {
  Normalization normalization;
  TriangleMesh garment;                    ///< welded garment, #Vg×3 / #Fg×3
  TriangleMesh avatar;                     ///< welded avatar, #Va×3 / #Fa×3
  std::optional<Skeleton> source_skeleton;  ///< in the garment's normalized frame
  std::optional<Skeleton> target_skeleton;  ///< in the avatar's normalized frame
};

/// normalize_scene, then every mesh and skeleton mapped into the normalized frame.
NormalizedScene make_normalized_scene(const Scene& scene);

}  // namespace gr
