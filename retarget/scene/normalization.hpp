#pragma once

#include <optional>

#include "core/common/types.hpp"
#include "retarget/scene/scene.hpp"

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

/// Spacing of the lattice that normalized coordinates are rounded to for a barrier support
/// `dhat` (normalized units): the largest power of two at most dhat / 2048, so 2^-20 (under
/// 5e-7 of the scene's size) at the default dhat.
/// Why: the fit is a non-convex minimization (cloth pressed onto a body has many nearly
/// equal folded states), so rounding-level differences in its input grow into visibly
/// different folds. On the lattice, a rescaled, moved or re-exported copy of an asset gives
/// the solver bit-identical input, hence the same garment, unless a coordinate lies within
/// rounding of a lattice midpoint. The spacing stays far below the gaps the barrier keeps
/// (a fraction of dhat), so the solver's avatar and the certified one differ by much less
/// than the final clearance.
double lattice_spacing(double dhat);

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
  double lattice = 0.0;  ///< coordinates are multiples of this (0: not rounded)
  TriangleMesh garment;  ///< welded garment, #Vg×3 / #Fg×3
  /// The garment's positions before the prepare stage untangled it (#Vg×3), which the
  /// change of shape is measured from; empty: garment.vertices are as given.
  MatrixX3d garment_as_given;
  TriangleMesh avatar;                      ///< welded avatar, #Va×3 / #Fa×3
  std::optional<Skeleton> source_skeleton;  ///< in the garment's normalized frame
  std::optional<Skeleton> target_skeleton;  ///< in the avatar's normalized frame
};

/// normalize_scene, then every mesh and skeleton mapped into the normalized frame and
/// rounded to multiples of `lattice` (a power of two; 0 keeps the mapped coordinates).
NormalizedScene make_normalized_scene(const Scene& scene, double lattice = 0.0);

/// The largest side of the bounding box of `points`: a mesh's size.
double largest_side(const Eigen::Ref<const MatrixX3d>& points);

/// Garment-to-avatar size ratios (largest bounding-box sides, placed on the avatar) the
/// pipeline retargets: a garment a hundredth of the avatar spans about ten barrier supports,
/// and one a hundred times its size covers nothing of it.
constexpr double kMinGarmentToAvatarSize = 1e-2;
constexpr double kMaxGarmentToAvatarSize = 1e2;

/// Refuses a garment and avatar whose sizes in the normalized scene differ beyond
/// [kMinGarmentToAvatarSize, kMaxGarmentToAvatarSize]: the solver's lengths (barrier
/// support, steps, voxels, all fractions of the normalized avatar) cannot serve both, and
/// such a pair is almost always two files in different units.
/// @throw InputError giving both sizes in their files' units.
void require_comparable_sizes(const Scene& scene, const NormalizedScene& normalized);

/// How far a garment that no skeleton places may lie from the avatar: the gap between
/// their bounding boxes, in avatar sizes (the box's largest side). A synthetic fin or patch
/// hovering just off a body lies a quarter of one away.
constexpr double kMaxGarmentGapToAvatarSize = 1.0;

/// Refuses a garment that no skeleton places and that lies further from the avatar than
/// kMaxGarmentGapToAvatarSize: without skeletons a garment is retargeted where it lies in
/// the avatar's frame, and one far beside the avatar (a file of another frame, or not moved
/// onto it) would be pulled onto the body from there and crushed.
/// @throw InputError naming both boxes' centres in the avatar's units.
void require_garment_on_avatar(const Scene& scene, const NormalizedScene& normalized);

}  // namespace gr
