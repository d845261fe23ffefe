#include "core/candidates/contact_mesh.hpp"

#include <algorithm>
#include <map>
#include <string>

#include "core/common/errors.hpp"
#include "core/mesh/unique_edges.hpp"

namespace gr {
namespace {

void check_faces(const MatrixX3i& faces, Eigen::Index vertex_count, const std::string& what) {
  if (faces.size() > 0 && (faces.minCoeff() < 0 || faces.maxCoeff() >= vertex_count))
    throw InputError("", 0, what + " face refers to a vertex out of range");
}

}  // namespace

ContactMesh ContactMesh::build(const TriangleMesh& garment, const TriangleMesh& avatar,
                               bool self_contact, const std::vector<int>& avatar_faces_used) {
  check_faces(garment.faces, garment.vertices.rows(), "garment");
  check_faces(avatar.faces, avatar.vertices.rows(), "avatar");
  ContactMesh mesh;
  mesh.garment_vertex_count = static_cast<int>(garment.vertices.rows());
  mesh.avatar_vertex_count = static_cast<int>(avatar.vertices.rows());
  mesh.self_contact = self_contact;
  mesh.garment_faces = garment.faces;
  mesh.garment_edges = unique_edges(garment.faces);

  if (avatar_faces_used.empty()) {
    mesh.avatar_faces = avatar.faces.array() + mesh.garment_vertex_count;
  } else {
    mesh.avatar_faces.resize(static_cast<Eigen::Index>(avatar_faces_used.size()), 3);
    for (std::size_t i = 0; i < avatar_faces_used.size(); ++i) {
      const int f = avatar_faces_used[i];
      if (f < 0 || f >= avatar.faces.rows())
        throw InputError(
            "", 0, "avatar face " + std::to_string(f) + " selected for contact does not exist");
      mesh.avatar_faces.row(static_cast<Eigen::Index>(i)) =
          avatar.faces.row(f).array() + mesh.garment_vertex_count;
    }
  }
  mesh.avatar_edges = unique_edges(mesh.avatar_faces);
  return mesh;
}

void ContactMesh::leave_out_of_avatar_contact(const std::vector<int>& faces) {
  if (faces.empty()) return;
  garment_face_meets_avatar.assign(static_cast<std::size_t>(garment_faces.rows()), 1);
  for (const int f : faces) {
    if (f < 0 || f >= garment_faces.rows())
      throw InputError("", 0, "garment face " + std::to_string(f) + " does not exist");
    garment_face_meets_avatar[static_cast<std::size_t>(f)] = 0;
  }
  garment_point_meets_avatar.assign(static_cast<std::size_t>(garment_vertex_count), 0);
  std::map<std::pair<int, int>, char> kept_edges;
  for (Eigen::Index f = 0; f < garment_faces.rows(); ++f) {
    if (!garment_face_meets_avatar[static_cast<std::size_t>(f)]) continue;
    for (int k = 0; k < 3; ++k) {
      const int a = garment_faces(f, k), b = garment_faces(f, (k + 1) % 3);
      garment_point_meets_avatar[static_cast<std::size_t>(a)] = 1;
      kept_edges[{std::min(a, b), std::max(a, b)}] = 1;
    }
  }
  garment_edge_meets_avatar.assign(static_cast<std::size_t>(garment_edges.rows()), 0);
  for (Eigen::Index e = 0; e < garment_edges.rows(); ++e) {
    const int a = garment_edges(e, 0), b = garment_edges(e, 1);
    garment_edge_meets_avatar[static_cast<std::size_t>(e)] =
        kept_edges.count({std::min(a, b), std::max(a, b)}) ? 1 : 0;
  }
}

}  // namespace gr
