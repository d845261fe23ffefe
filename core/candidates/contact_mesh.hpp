#pragma once

#include <vector>

#include "core/common/types.hpp"

namespace gr {

/// Garment and avatar stacked in one vertex array for contact. Rows
/// [0, garment_vertex_count) of a stacked position matrix are garment vertices, rows
/// [garment_vertex_count, garment_vertex_count + avatar_vertex_count) avatar vertices.
/// Every index below is into the stacked array. Avatar–avatar pairs are never modelled
/// (real avatars intersect themselves).
struct ContactMesh {
  int garment_vertex_count = 0;
  int avatar_vertex_count = 0;
  MatrixX3i garment_faces;   ///< #Fg×3
  MatrixX2i garment_edges;   ///< #Eg×2, each undirected edge once
  MatrixX3i avatar_faces;    ///< #Fa×3, offset by garment_vertex_count; may be a subset
  MatrixX2i avatar_edges;    ///< #Ea×2, edges of avatar_faces
  bool self_contact = true;  ///< model garment–garment pairs that share no vertex
  /// Leave out self pairs inside a garment region that provably cannot fold onto itself
  /// during the motion at hand (candidates/fold_free_regions.hpp); off: search them all.
  bool cull_fold_free = true;
  /// Per garment vertex, the tangle it belongs to (-1: none): where the garment crosses
  /// itself as given, the crossing faces and their neighbourhood. A self pair whose
  /// vertices all lie in one tangle is not modelled: it may cross already, and the barrier
  /// and CCD leave inherited crossings as they are. Empty: no tangle.
  std::vector<int> garment_tangles;

  int vertex_count() const { return garment_vertex_count + avatar_vertex_count; }

  /// Stacks the two meshes. `avatar_faces_used` (row indices into avatar.faces) keeps only
  /// avatar faces the garment can reach; empty means all. Avatar vertices no kept face uses
  /// take part in no pair.
  /// @throw InputError when a face refers to a missing vertex or a selected avatar face
  ///        does not exist.
  static ContactMesh build(const TriangleMesh& garment, const TriangleMesh& avatar,
                           bool self_contact, const std::vector<int>& avatar_faces_used = {});
};

}  // namespace gr
