#pragma once

#include <array>
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
  /// itself as given, the crossing faces and their neighbourhood. Empty: no tangle.
  std::vector<int> garment_tangles;
  /// Garment face pairs (rows of garment_faces, first < second, sorted) that cross as the
  /// solve starts: a crossing the input came with and the untangle left.
  std::vector<std::array<int, 2>> garment_crossing_faces;
  /// Self pairs that are not modelled (sorted self_pair_key values): pairs that touch, or
  /// all but touch, at the start and every face pair of which crosses then
  /// (crossing_pairs_closer_than). Every other pair stays apart under the barrier and CCD,
  /// and no face pair can start crossing without one of its point–triangle or edge–edge
  /// pairs meeting, all of which are modelled when it does not cross at the start: the
  /// crossings the garment starts with are kept as they are, and none is added.
  std::vector<std::array<int, 5>> unmodelled_self_pairs;
  /// Per garment vertex, garment edge (rows of garment_edges) and garment face: whether it
  /// takes part in garment–avatar pairs (leave_out_of_avatar_contact). Empty: all do.
  std::vector<char> garment_point_meets_avatar;
  std::vector<char> garment_edge_meets_avatar;
  std::vector<char> garment_face_meets_avatar;

  int vertex_count() const { return garment_vertex_count + avatar_vertex_count; }

  /// Stacks the two meshes. `avatar_faces_used` (row indices into avatar.faces) keeps only
  /// avatar faces the garment can reach; empty means all. Avatar vertices no kept face uses
  /// take part in no pair.
  /// @throw InputError when a face refers to a missing vertex or a selected avatar face
  ///        does not exist.
  /// Leaves garment faces (rows of garment_faces) out of garment–avatar pairs: faces the
  /// avatar passes through as given, such as a cap around a bone. An edge or vertex still
  /// meets the avatar when a face that is kept holds it. Self pairs are unchanged.
  /// @throw InputError when a face does not exist.
  void leave_out_of_avatar_contact(const std::vector<int>& faces);

  static ContactMesh build(const TriangleMesh& garment, const TriangleMesh& avatar,
                           bool self_contact, const std::vector<int>& avatar_faces_used = {});
};

}  // namespace gr
