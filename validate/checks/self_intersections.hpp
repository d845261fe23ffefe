#pragma once

#include <cstddef>
#include <limits>
#include <vector>

#include "core/common/types.hpp"
#include "validate/checks/mesh_intersections.hpp"

namespace gr {

/// Self-intersections of one mesh, with what could not be decided.
struct SelfIntersections {
  FacePairList pairs;  ///< intersecting pairs (first < second)
  /// Neighbouring pairs (sharing a vertex) in which a face is degenerate: "overlap beyond
  /// the shared part" has no clean meaning for a segment lying on its neighbour's edge, so
  /// these are not tested. The degenerate faces themselves are reported by
  /// find_degenerate_faces; pairs of a degenerate face with a face it shares no vertex
  /// with are tested like any other.
  std::size_t untested_degenerate_neighbours = 0;
};

/// Pairs of distinct faces of `mesh` that intersect, decided exactly (CGAL's
/// Exact_predicates_inexact_constructions_kernel after a box-intersection broad phase).
/// Vertices are identified by position: rows of `mesh.vertices` with identical
/// coordinates are one vertex (see position_identity), so faces across a UV seam are
/// neighbours. For two non-degenerate faces:
/// - sharing no vertex: intersecting iff they have any point in common (touching counts);
/// - sharing an edge: intersecting iff the two opposite corners are coplanar with the
///   edge and on the same side of it (a fold flat onto itself);
/// - sharing one vertex: intersecting iff they meet anywhere else, decided by testing each
///   face's edge opposite the shared vertex against the other face;
/// - sharing all three corners (a duplicated face): intersecting.
/// A degenerate face (exactly collinear corners) is tested as the segment or point it is
/// against faces it shares no vertex with; see SelfIntersections for its neighbours.
/// @param max_listed how many pairs to list; all are counted.
SelfIntersections find_self_intersecting_face_pairs(
    const TriangleMesh& mesh, std::size_t max_listed = std::numeric_limits<std::size_t>::max());

/// The pairs of `candidates` (distinct faces of `mesh`, each pair once) that intersect,
/// decided as find_self_intersecting_face_pairs decides them: for a caller whose own broad
/// phase knows which pairs can meet, such as a few moved faces and their surroundings.
SelfIntersections self_intersecting_among(
    const TriangleMesh& mesh, const std::vector<FacePair>& candidates,
    std::size_t max_listed = std::numeric_limits<std::size_t>::max());

}  // namespace gr
