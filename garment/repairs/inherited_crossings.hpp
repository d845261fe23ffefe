#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "core/common/types.hpp"
#include "core/energies/attachment_energy.hpp"
#include "validate/checks/mesh_intersections.hpp"

namespace gr {

/// Where a garment crosses itself as given: production garments lay collars, straps and
/// pockets through their base cloth. The run keeps these crossings as they are (inherited)
/// and certifies that it adds none.
struct InheritedCrossings {
  std::vector<FacePair> pairs;  ///< crossing face pairs (first < second), simulation faces
  /// Per garment vertex, its tangle (GarmentScene::garment_tangles), -1 outside every one;
  /// empty when nothing crosses.
  std::vector<int> tangles;
  int tangle_count = 0;
  int tangled_vertices = 0;
  /// Vertices of pieces that cross another piece, attached to it (attach_crossing_pieces).
  std::vector<Attachment> attachments;
};

/// The tangles of `pairs`: the vertices of each crossing face and those within `rings`
/// edges of them, grouped so that both faces of a crossing pair, and overlapping
/// neighbourhoods, share one tangle. Each of `groups` (vertex ids, e.g. a split edge's
/// vertices and their copies) makes a tangle the same way.
/// @param pairs face rows of `garment`.
InheritedCrossings tangles_of(const TriangleMesh& garment, std::vector<FacePair> pairs, int rings,
                              const std::vector<std::vector<int>>& groups = {});

/// Pieces (connected parts of the garment) that cross another piece as given, a belt
/// through a dress, a strap through a shirt, follow it: every vertex of the smaller piece
/// of a crossing pair is attached to the triangle of the other piece whose centroid is
/// nearest, keeping its offset from that centroid. Crossings within one piece attach
/// nothing, nor do crossings between layers of an outfit: each garment moves on its own,
/// and a whole skirt tied to the jacket whose hem crosses its waistband would be dragged
/// wherever the jacket goes.
/// @param pairs face rows of `garment`.
/// @param face_layer per face of `garment`, its layer; empty: one layer.
/// @param pieces set to the number of pieces attached.
std::vector<Attachment> attach_crossing_pieces(const TriangleMesh& garment,
                                               const std::vector<FacePair>& pairs,
                                               const std::vector<int>& face_layer, int& pieces);

/// What the crossings repair kept (report.json `inherited_crossings`): the crossings of the
/// garment with itself as given, and the pieces attached through them.
struct InheritedReport {
  int pairs = 0;                         ///< crossing face pairs of the input
  int tangles = 0;                       ///< groups of crossings, each left out of self contact
  int tangled_vertices = 0;              ///< vertices in them
  int still_crossing = 0;                ///< of the pairs, those the written garment still has
  int attached_pieces = 0;               ///< pieces crossing another piece, attached to it
  std::vector<FacePair> document_pairs;  ///< the pairs as input face ids (0-based)
};

nlohmann::json to_json(const InheritedReport& report);

/// Per face of `garment`, whether a corner lies in one of `crossings`' tangles.
std::vector<char> tangled_faces(const TriangleMesh& garment, const InheritedCrossings& crossings);

}  // namespace gr
