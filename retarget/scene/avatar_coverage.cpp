#include "retarget/scene/avatar_coverage.hpp"

#include <algorithm>
#include <numeric>

#include <fmt/format.h>

#include "core/skeleton/skin_matching.hpp"

namespace gr {

namespace {

/// Per bone, the area of the faces of `mesh` whose centroids lie nearest it.
std::vector<double> area_per_bone(const TriangleMesh& mesh, const Skeleton& skeleton) {
  std::vector<double> area(static_cast<std::size_t>(skeleton.bones.rows()), 0.0);
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    const Vector3d a = mesh.vertices.row(mesh.faces(f, 0)).transpose();
    const Vector3d b = mesh.vertices.row(mesh.faces(f, 1)).transpose();
    const Vector3d c = mesh.vertices.row(mesh.faces(f, 2)).transpose();
    const auto bone = static_cast<std::size_t>(nearest_bone(skeleton, (a + b + c) / 3.0).first);
    area[bone] += 0.5 * (b - a).cross(c - a).norm();
  }
  return area;
}

}  // namespace

AvatarCoverage measure_avatar_coverage(const NormalizedScene& normalized) {
  AvatarCoverage coverage;
  if (!normalized.source_skeleton || !normalized.target_skeleton) return coverage;
  coverage.garment_area = area_per_bone(normalized.garment, *normalized.source_skeleton);
  coverage.avatar_area = area_per_bone(normalized.avatar, *normalized.target_skeleton);
  const double garment_total =
      std::accumulate(coverage.garment_area.begin(), coverage.garment_area.end(), 0.0);
  if (garment_total <= 0.0) return coverage;
  for (std::size_t b = 0; b < coverage.garment_area.size(); ++b)
    if (coverage.garment_area[b] > 0.0 &&
        coverage.avatar_area[b] < kMinAvatarToGarmentArea * coverage.garment_area[b]) {
      coverage.uncovered_bones.push_back(static_cast<int>(b));
      coverage.uncovered_share += coverage.garment_area[b] / garment_total;
    }
  std::stable_sort(coverage.uncovered_bones.begin(), coverage.uncovered_bones.end(),
                   [&](int a, int b) {
                     return coverage.garment_area[static_cast<std::size_t>(a)] >
                            coverage.garment_area[static_cast<std::size_t>(b)];
                   });
  return coverage;
}

std::string bone_name(const Skeleton& skeleton, const std::vector<std::string>& joint_names,
                      int bone) {
  const int first = skeleton.bones(bone, 0);
  const int second = skeleton.bones(bone, 1);
  if (static_cast<int>(joint_names.size()) != skeleton.joints.rows())
    return fmt::format("bone {}", bone);
  return joint_names[static_cast<std::size_t>(first)] + "-" +
         joint_names[static_cast<std::size_t>(second)];
}

}  // namespace gr
