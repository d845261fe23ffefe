#pragma once

#include <string>
#include <vector>

#include "core/common/types.hpp"

namespace gr {

/// Skeleton-free scenes: a garment placed over a simple body that pokes through it, as a
/// change of shape or pose leaves a garment on an avatar. They exercise the level-set path
/// (no skeletons) on every kind of contact: a cap (patch over a sphere), a point (patch
/// over a cone's tip), a ring (patch over a torus), edges (sleeve around a box) and a
/// whole band (sleeve around a sphere).
enum class SkeletonFreeFamily { kPatchSphere, kPatchCone, kPatchTorus, kSleeveBox, kSleeveSphere };

/// "patch_sphere", "patch_cone", "patch_torus", "sleeve_box" or "sleeve_sphere".
const char* to_string(SkeletonFreeFamily family);

/// Every family, in declaration order.
std::vector<SkeletonFreeFamily> all_skeleton_free_families();

/// One member of a family: the garment's resolution, its offset from the centred
/// placement (in body units, across the contact) and a rigid motion and scale of the
/// whole scene (other axes, origins and units than the canonical Z-up, unit-sized body).
struct SkeletonFreeVariant {
  int resolution = 16;  ///< garment cells across (patches) or around (sleeves)
  double offset = 0.0;  ///< garment shift across the contact, body units
  /// Rotation of the whole scene about (1, 1, 1) in degrees, then its scale and origin.
  double turn_degrees = 0.0;
  double scale = 1.0;
  Vector3d origin = Vector3d::Zero();  ///< pass Vector3d::Zero(), not {}: Eigen leaves {} unset
};

struct SkeletonFreeScene {
  std::string name;  ///< family, resolution, offset and motion, for messages
  TriangleMesh garment;
  TriangleMesh avatar;
};

/// The scene of `family` in `variant`. Avatars are closed and outward oriented; garments
/// are open, with consistently oriented faces.
/// @throw std::invalid_argument when variant.resolution < 4 or variant.scale <= 0.
SkeletonFreeScene make_skeleton_free_scene(SkeletonFreeFamily family,
                                           const SkeletonFreeVariant& variant);

}  // namespace gr
