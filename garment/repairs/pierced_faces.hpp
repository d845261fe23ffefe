#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/common/types.hpp"
#include "core/energies/distance_field.hpp"
#include "core/io/gltf_document.hpp"
#include "core/io/obj_document.hpp"
#include "core/io/rig_files.hpp"
#include "validate/checks/mesh_intersections.hpp"

namespace gr {

/// Garment faces that a skeleton's bones pass through, decided exactly (each bone tested
/// as the segment between its joints): a closed shell or a cap (trousers closed at the
/// waist and ankles) around the body. A skeleton shrink collapses the avatar onto the
/// bones, so no shrunk avatar is free of such a garment.
/// @return (garment face, bone) pairs, sorted by face.
std::vector<FacePair> faces_pierced_by_bones(const TriangleMesh& garment, const Skeleton& skeleton);

/// What the pierced-faces repair did (report.json `pierced_faces`): garment faces the avatar
/// passes through as given, left out of the avatar contact, and those opened at the end.
struct PiercedReport {
  int shrinks = 0;                  ///< shrinks tried until one was free of the rest of the garment
  std::vector<int> document_faces;  ///< left out of the avatar contact, input face ids
  std::vector<std::string> bones;   ///< source bones through garment faces, "a-b"
  std::vector<int> opened_document_faces;  ///< left out of the written file, input face ids
};

nlohmann::json to_json(const PiercedReport& report);

/// Faces the source bones pierce, where the pierced-faces repair starts.
struct PiercedByBones {
  std::vector<FacePair> pairs;     ///< (garment face, bone), as faces_pierced_by_bones
  std::vector<int> faces;          ///< the pierced faces, in pairs' order (repeats kept)
  std::vector<std::string> bones;  ///< the bones through them, "a-b" by joint name, sorted
};

/// faces_pierced_by_bones with the bones named (`joint_names` when given, else "joint j").
PiercedByBones pierced_by_bones(const TriangleMesh& garment, const Skeleton& skeleton,
                                const std::vector<std::string>& joint_names);

/// One line naming the pierced faces (input face ids `face_to_obj`, 1-based) and the bones
/// through them (`joint_names` when given, else joint indices).
std::string describe_pierced_faces(const std::vector<FacePair>& pierced,
                                   const std::vector<int>& face_to_obj, const Skeleton& skeleton,
                                   const std::vector<std::string>& joint_names);

/// The faces whose three corners lie within `rings` edges of a corner of `seeds` (rows of
/// `faces`), seeds included; sorted.
std::vector<int> faces_around(const TriangleMesh& mesh, const std::vector<int>& seeds, int rings);

/// The garment faces a shrunk avatar crosses (exactly), and those holding a garment vertex
/// inside it (the shrink's winding-number test): what keeps that shrink from being free of
/// the garment. Sorted.
std::vector<int> faces_against_shrunk_avatar(const TriangleMesh& shrunk_avatar,
                                             const TriangleMesh& garment);

/// The garment without `left_out` (sorted face rows), renumbered to the vertices the kept
/// faces use: the surface a shrunk avatar must be free of when those faces are left out of
/// the avatar contact.
TriangleMesh surface_without(const TriangleMesh& garment, const std::vector<int>& left_out);

/// Of the faces left out of the avatar contact, those the avatar still passes through or
/// holds at the end: crossing an avatar face (exactly), or with a corner closer than
/// `clearance` to the avatar or inside it (`distance`). They are opened: left out of the
/// written garment, so that what is written is free of the avatar. Sorted.
std::vector<int> faces_to_open(const TriangleMesh& garment, const TriangleMesh& avatar,
                               const DistanceField& distance, const std::vector<int>& left_out,
                               double clearance);

/// Leaves `faces` (sorted document face ids) out of a document to be written: its groups
/// and materials, and a glTF source's primitives (when given), keep the faces that stay.
/// Positions stay as they are.
void remove_document_faces(ObjDocument& document, GltfDocument* gltf,
                           const std::vector<int>& faces);

/// Face ids of a document before remove_document_faces(`removed`) as ids after it: -1 for a
/// removed face.
std::vector<int> face_ids_after_removal(int face_count, const std::vector<int>& removed);

}  // namespace gr
