#pragma once

#include <string>
#include <vector>

#include "core/common/types.hpp"
#include "core/io/rig_files.hpp"
#include "validate/checks/mesh_intersections.hpp"

namespace gr {

/// Garment faces that a skeleton's bones pass through, decided exactly (each bone tested
/// as the segment between its joints): a closed shell or a cap (trousers closed at the
/// waist and ankles) around the body. A skeleton shrink collapses the avatar onto the
/// bones, so no shrunk avatar is free of such a garment.
/// @return (garment face, bone) pairs, sorted by face.
std::vector<FacePair> faces_pierced_by_bones(const TriangleMesh& garment, const Skeleton& skeleton);

/// One line naming the pierced faces (input face ids `face_to_obj`, 1-based) and the bones
/// through them (`joint_names` when given, else joint indices).
std::string describe_pierced_faces(const std::vector<FacePair>& pierced,
                                   const std::vector<int>& face_to_obj, const Skeleton& skeleton,
                                   const std::vector<std::string>& joint_names);

}  // namespace gr
