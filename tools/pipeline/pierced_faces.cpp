#include "tools/pipeline/pierced_faces.hpp"

#include <set>

#include <fmt/format.h>

namespace gr {

std::vector<FacePair> faces_pierced_by_bones(const TriangleMesh& garment,
                                             const Skeleton& skeleton) {
  // Each bone as a degenerate triangle (a, b, a): the exact test takes it as its segment.
  TriangleMesh bones{skeleton.joints, MatrixX3i(skeleton.bones.rows(), 3)};
  for (Eigen::Index b = 0; b < skeleton.bones.rows(); ++b)
    bones.faces.row(b) << skeleton.bones(b, 0), skeleton.bones(b, 1), skeleton.bones(b, 0);
  return find_intersecting_face_pairs(garment, bones).pairs;
}

std::string describe_pierced_faces(const std::vector<FacePair>& pierced,
                                   const std::vector<int>& face_to_obj, const Skeleton& skeleton,
                                   const std::vector<std::string>& joint_names) {
  const auto joint = [&](int j) {
    return j < static_cast<int>(joint_names.size()) ? joint_names[static_cast<std::size_t>(j)]
                                                    : fmt::format("joint {}", j);
  };
  std::set<int> faces, bones;
  for (const FacePair& p : pierced) {
    faces.insert(face_to_obj[static_cast<std::size_t>(p.first)] + 1);
    bones.insert(p.second);
  }
  constexpr std::size_t kNamed = 6;
  std::string face_list, bone_list;
  std::size_t named = 0;
  for (const int f : faces) {
    if (named++ == kNamed) break;
    face_list += (face_list.empty() ? "" : ", ") + std::to_string(f);
  }
  named = 0;
  for (const int b : bones) {
    if (named++ == kNamed) break;
    bone_list += fmt::format("{}{}-{}", bone_list.empty() ? "" : ", ", joint(skeleton.bones(b, 0)),
                             joint(skeleton.bones(b, 1)));
  }
  return fmt::format(
      "the source skeleton's bones pass through {} garment faces ({}{}) along {} bones ({}{}): "
      "a closed shell or cap around the body, which no skeleton shrink can free; open those "
      "faces in the asset",
      faces.size(), face_list, faces.size() > kNamed ? ", ..." : "", bones.size(), bone_list,
      bones.size() > kNamed ? ", ..." : "");
}

}  // namespace gr
