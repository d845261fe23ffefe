#pragma once

#include <array>
#include <vector>

#include "core/candidates/contact_mesh.hpp"

namespace gr {

/// A point and a triangle that may come into contact; indices into the stacked array.
struct PointTriangleCandidate {
  int point;
  std::array<int, 3> triangle;
};

/// Two edges that may come into contact; indices into the stacked array.
struct EdgeEdgeCandidate {
  std::array<int, 2> edge_a;
  std::array<int, 2> edge_b;
};

/// Pairs the narrow phase must look at: garment vertex–avatar triangle, avatar
/// vertex–garment triangle, garment edge–avatar edge, and (when self_contact is on)
/// garment–garment point–triangle and edge–edge pairs that share no vertex.
struct Candidates {
  std::vector<PointTriangleCandidate> point_triangle;
  std::vector<EdgeEdgeCandidate> edge_edge;
  std::size_t size() const { return point_triangle.size() + edge_edge.size(); }
  bool empty() const { return size() == 0; }
};

/// Every pair whose distance at `V` may be below `inflation_radius` (a superset: pairs
/// whose bounding boxes come within the radius). Built from bounding volume hierarchies
/// rebuilt on every call (core/broad_phase/bvh.hpp); the order of the lists is fixed by
/// the geometry, the same on any thread count.
/// @param V stacked positions, #(garment+avatar)×3, in normalized scene units.
/// @throw std::invalid_argument when V's row count is not mesh.vertex_count().
Candidates find_candidates(const ContactMesh& mesh, const Eigen::Ref<const MatrixX3d>& V,
                           double inflation_radius);

/// Every pair whose swept volumes along the linear motion V0 → V1 come within
/// `inflation_radius` of each other (a superset of the pairs that CCD must check): each
/// vertex's box spans its start and end positions.
/// @throw std::invalid_argument when V0 or V1 has the wrong row count.
Candidates find_swept_candidates(const ContactMesh& mesh, const Eigen::Ref<const MatrixX3d>& V0,
                                 const Eigen::Ref<const MatrixX3d>& V1, double inflation_radius);

}  // namespace gr
