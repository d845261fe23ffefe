#pragma once

#include <cstddef>
#include <vector>

#include "core/common/types.hpp"

namespace gr {

/// The smallest distance between two meshes and where it is reached.
struct Clearance {
  double distance = 0.0;  ///< in the meshes' own units; 0 when they touch or intersect
  int first_face = -1;    ///< face of the first mesh holding the closest point
  int second_face = -1;   ///< face of the second mesh holding the closest point
  Vector3d first_point = Vector3d::Zero();
  Vector3d second_point = Vector3d::Zero();
};

/// Minimum distance between the surfaces of two triangle meshes, with FCL
/// (fcl::BVHModel<OBBRSSd> on each, fcl::distance with nearest points). Computed in
/// doubles: use it as a measure, and the exact intersection tests for a yes/no answer.
/// @pre both meshes have at least one face.
Clearance minimum_clearance(const TriangleMesh& first, const TriangleMesh& second);

/// Vertices of `points_mesh` that some face uses and that lie closer than `threshold`
/// (strictly, in the meshes' units) to the surface of `surface`, by CGAL AABB-tree
/// point–triangle distances (degenerate faces measured as the segments they are).
/// Rows at identical coordinates count once, as the smallest row index.
/// @return row indices of `points_mesh.vertices`, increasing.
/// @pre `surface` has at least one face; threshold >= 0.
std::vector<int> vertices_closer_than(const TriangleMesh& points_mesh, const TriangleMesh& surface,
                                      double threshold);

}  // namespace gr
