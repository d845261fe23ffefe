#pragma once

#include <string>
#include <vector>

#include "retarget/scene/normalization.hpp"

namespace gr {

/// How much of the garment lies around bones the avatar has (almost) no surface around: a
/// body cut away under its own clothes, or an avatar read without the mesh of a part (a
/// head left out of --avatar-mesh). The fit there has nothing to rest the garment on.
struct AvatarCoverage {
  /// Per bone of the skeletons (the same bones in both), the garment's area nearest it on
  /// the source skeleton and the avatar's nearest it on the target's (normalized units).
  std::vector<double> garment_area;
  std::vector<double> avatar_area;
  /// Bones around which the avatar has less than kMinAvatarToGarmentArea of the garment's
  /// area, most garment area first.
  std::vector<int> uncovered_bones;
  double uncovered_share = 0.0;  ///< of the garment's area, around those bones
};

/// Around a bone, an avatar with less surface than this fraction of the garment's lacks the
/// part: a neck ring under a head of hair, an ankle's cut under a shoe.
constexpr double kMinAvatarToGarmentArea = 0.05;

/// Measures where the avatar lacks surface under the garment: each garment face (by its
/// centroid) goes to its nearest source bone, each avatar face to its nearest target bone.
/// Empty without both skeletons.
AvatarCoverage measure_avatar_coverage(const NormalizedScene& normalized);

/// A bone named by its joints ("Neck-Head"), or by its index when the joints have no names.
std::string bone_name(const Skeleton& skeleton, const std::vector<std::string>& joint_names,
                      int bone);

}  // namespace gr
