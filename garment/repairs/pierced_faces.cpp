#include "garment/repairs/pierced_faces.hpp"

#include <algorithm>
#include <set>

#include <fmt/format.h>

#include "core/mesh/vertex_neighbours.hpp"
#include "shrink/shrunk_avatar/shrink_certification.hpp"

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

std::vector<int> faces_around(const TriangleMesh& mesh, const std::vector<int>& seeds, int rings) {
  const auto n = static_cast<std::size_t>(mesh.vertices.rows());
  const auto neighbours = vertex_neighbours(mesh);
  std::vector<char> reached(n, 0);
  std::vector<int> front;
  for (const int f : seeds)
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.faces(f, k);
      if (!reached[static_cast<std::size_t>(v)]) {
        reached[static_cast<std::size_t>(v)] = 1;
        front.push_back(v);
      }
    }
  for (int ring = 0; ring < rings && !front.empty(); ++ring) {
    std::vector<int> next;
    for (const int v : front)
      for (const int u : neighbours[static_cast<std::size_t>(v)])
        if (!reached[static_cast<std::size_t>(u)]) {
          reached[static_cast<std::size_t>(u)] = 1;
          next.push_back(u);
        }
    front = std::move(next);
  }
  std::vector<int> faces;
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    if (reached[static_cast<std::size_t>(mesh.faces(f, 0))] &&
        reached[static_cast<std::size_t>(mesh.faces(f, 1))] &&
        reached[static_cast<std::size_t>(mesh.faces(f, 2))])
      faces.push_back(static_cast<int>(f));
  return faces;
}

std::vector<int> faces_against_shrunk_avatar(const TriangleMesh& shrunk_avatar,
                                             const TriangleMesh& garment) {
  std::set<int> faces;
  for (const FacePair& p : find_intersecting_face_pairs(shrunk_avatar, garment).pairs)
    faces.insert(p.second);
  std::vector<char> inside(static_cast<std::size_t>(garment.vertices.rows()), 0);
  for (const int v : garment_vertices_inside(shrunk_avatar, garment.vertices))
    inside[static_cast<std::size_t>(v)] = 1;
  for (Eigen::Index f = 0; f < garment.faces.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (inside[static_cast<std::size_t>(garment.faces(f, k))]) faces.insert(static_cast<int>(f));
  return {faces.begin(), faces.end()};
}

TriangleMesh surface_without(const TriangleMesh& garment, const std::vector<int>& left_out) {
  std::vector<int> renumbered(static_cast<std::size_t>(garment.vertices.rows()), -1);
  std::vector<int> kept_vertices;
  MatrixX3i faces(garment.faces.rows() - static_cast<Eigen::Index>(left_out.size()), 3);
  Eigen::Index row = 0;
  for (Eigen::Index f = 0; f < garment.faces.rows(); ++f) {
    if (std::binary_search(left_out.begin(), left_out.end(), static_cast<int>(f))) continue;
    for (int k = 0; k < 3; ++k) {
      int& id = renumbered[static_cast<std::size_t>(garment.faces(f, k))];
      if (id < 0) {
        id = static_cast<int>(kept_vertices.size());
        kept_vertices.push_back(garment.faces(f, k));
      }
      faces(row, k) = id;
    }
    ++row;
  }
  MatrixX3d vertices(static_cast<Eigen::Index>(kept_vertices.size()), 3);
  for (std::size_t i = 0; i < kept_vertices.size(); ++i)
    vertices.row(static_cast<Eigen::Index>(i)) = garment.vertices.row(kept_vertices[i]);
  return {vertices, faces};
}

std::vector<int> faces_to_open(const TriangleMesh& garment, const TriangleMesh& avatar,
                               const DistanceField& distance, const std::vector<int>& left_out,
                               double clearance) {
  if (left_out.empty()) return {};
  TriangleMesh candidates{garment.vertices,
                          MatrixX3i(static_cast<Eigen::Index>(left_out.size()), 3)};
  for (std::size_t i = 0; i < left_out.size(); ++i)
    candidates.faces.row(static_cast<Eigen::Index>(i)) = garment.faces.row(left_out[i]);
  std::set<int> opened;
  for (const FacePair& p : find_intersecting_face_pairs(candidates, avatar).pairs)
    opened.insert(left_out[static_cast<std::size_t>(p.first)]);
  for (const int f : left_out)
    for (int k = 0; k < 3; ++k)
      if (distance.evaluate(garment.vertices.row(garment.faces(f, k)).transpose()) < clearance)
        opened.insert(f);
  return {opened.begin(), opened.end()};
}

std::vector<int> face_ids_after_removal(int face_count, const std::vector<int>& removed) {
  std::vector<int> after(static_cast<std::size_t>(face_count), -1);
  int next = 0;
  for (int f = 0; f < face_count; ++f)
    if (!std::binary_search(removed.begin(), removed.end(), f))
      after[static_cast<std::size_t>(f)] = next++;
  return after;
}

void remove_document_faces(ObjDocument& document, GltfDocument* gltf,
                           const std::vector<int>& faces) {
  if (faces.empty()) return;
  const auto count = static_cast<int>(document.faces.size());
  const std::vector<int> after = face_ids_after_removal(count, faces);
  // kept_before[f]: the faces kept before face f (f may be one past the end).
  std::vector<int> kept_before(static_cast<std::size_t>(count) + 1, 0);
  for (int f = 0; f < count; ++f)
    kept_before[static_cast<std::size_t>(f) + 1] =
        kept_before[static_cast<std::size_t>(f)] + (after[static_cast<std::size_t>(f)] >= 0);
  const auto kept_until = [&](int face) {
    return kept_before[static_cast<std::size_t>(std::clamp(face, 0, count))];
  };
  std::vector<std::array<ObjCorner, 3>> kept;
  for (int f = 0; f < count; ++f)
    if (after[static_cast<std::size_t>(f)] >= 0)
      kept.push_back(document.faces[static_cast<std::size_t>(f)]);
  for (ObjStatement& statement : document.statements)
    statement.first_face = kept_until(statement.first_face);
  if (gltf)
    for (GltfPrimitive& primitive : gltf->primitives) {
      const int end = kept_until(primitive.first_face + primitive.face_count);
      primitive.first_face = kept_until(primitive.first_face);
      primitive.face_count = end - primitive.first_face;
    }
  document.faces = std::move(kept);
}

nlohmann::json to_json(const PiercedReport& report) {
  return {{"shrinks", report.shrinks},
          {"bones", report.bones},
          {"left_out_of_contact", report.document_faces},
          {"opened", report.opened_document_faces},
          {"meaning",
           "garment faces (0-based input faces) the avatar passes through as given, such as a cap "
           "around a bone: left out of the garment-avatar contact so that the avatar can shrink "
           "free of the rest; those the avatar still passes through at the end are opened, "
           "left out of the written file"}};
}

PiercedByBones pierced_by_bones(const TriangleMesh& garment, const Skeleton& skeleton,
                                const std::vector<std::string>& joint_names) {
  PiercedByBones pierced;
  pierced.pairs = faces_pierced_by_bones(garment, skeleton);
  const auto joint = [&](int j) {
    return j < static_cast<int>(joint_names.size()) ? joint_names[static_cast<std::size_t>(j)]
                                                    : fmt::format("joint {}", j);
  };
  std::set<std::string> bones;
  for (const FacePair& p : pierced.pairs) {
    pierced.faces.push_back(p.first);
    bones.insert(joint(skeleton.bones(p.second, 0)) + "-" + joint(skeleton.bones(p.second, 1)));
  }
  pierced.bones.assign(bones.begin(), bones.end());
  return pierced;
}

}  // namespace gr
