#pragma once

#include <array>
#include <map>
#include <utility>
#include <vector>

#include "core/common/types.hpp"

namespace gr {

/// A hierarchy of garment regions, for leaving self-contact out where the garment cannot
/// fold onto itself. The leaves are small patches that partition the faces; every other
/// region joins two neighbouring regions. A region that is a topological disk and whose
/// projection along its mean normal stays one-to-one over a motion cannot touch itself
/// during it (see `stays_fold_free`): pairs inside it need neither barrier nor CCD.
struct GarmentRegions {
  struct Region {
    std::vector<int> faces;     ///< garment face rows
    std::vector<int> vertices;  ///< every vertex of those faces
    /// The boundary loop's vertices in the faces' orientation; empty unless a disk.
    std::vector<int> boundary;
    /// Connected, consistently oriented, manifold, one boundary loop, Euler characteristic 1.
    bool disk = false;
    std::array<int, 2> children{-1, -1};  ///< region ids; -1 for a leaf
    int leaf = -1;                        ///< leaf index, -1 for a joined region
  };
  /// Children come before their parent.
  std::vector<Region> regions;
  std::vector<int> roots;        ///< regions no other joins (one per piece, or more)
  std::vector<int> leaves;       ///< region id of each leaf
  std::vector<int> face_leaf;    ///< per garment face
  std::vector<int> vertex_leaf;  ///< per garment vertex, a leaf that holds it; -1 if no face does
  std::vector<int> edge_leaf;    ///< per row of the edge list given, a leaf that holds it
  /// Each two leaves that share a consistently oriented edge, joined: pairs across their
  /// seam need no search when their union stays fold free. Keyed by (smaller, larger) leaf.
  std::map<std::pair<int, int>, Region> leaf_unions;

  bool is_leaf(int region) const { return regions[static_cast<std::size_t>(region)].leaf >= 0; }
};

/// Leaves: patches grown face by face across consistently oriented manifold edges, each up
/// to `max_leaf_faces` faces whose normals at V stay within `max_normal_angle` (radians) of
/// its first face's (degenerate faces are leaves of their own). Then, level by level, each
/// region joins the neighbour it shares the most edges with.
/// @param faces garment faces (#F×3), @param edges its unique edges (#E×2),
/// @param V garment positions (at least max index + 1 rows).
GarmentRegions build_garment_regions(const MatrixX3i& faces, const MatrixX2i& edges,
                                     const Eigen::Ref<const MatrixX3d>& V, int max_leaf_faces = 32,
                                     double max_normal_angle = 1.0);

/// Whether the region cannot touch itself anywhere along the linear motion V0 → V1 (rows
/// indexed as `faces`; V0 and V1 may be the same matrix for a static check). Let a be the
/// region's mean normal at V0 and P the projection onto the plane normal to a. It holds when
/// the region is a disk and, for every τ in [0, 1]:
/// - every face projects with positive orientation (a · n(τ) > 0, a quadratic in τ tested
///   through its Bernstein coefficients);
/// - the projected boundary loop is a simple curve: consecutive edges never fold back onto
///   each other (the cross or the dot product of their directions keeps its sign), and any
///   two other edges stay apart (their swept hulls, taken relative to the moving centroid,
///   have a separating axis).
/// A simple boundary around positively oriented faces winds once around each point it
/// encloses, so each such point is covered by one face: P is one-to-one on the region and
/// no two of its points meet in space. Every sign is required with a margin far above
/// rounding. Conservative: a false answer says nothing.
/// With a `clearance`, projected face heights and the gaps between those boundary hulls
/// must also exceed it, which keeps pairs inside the region (that share no vertex) about
/// that far apart: leaving them out of a barrier of that support changes next to nothing.
bool stays_fold_free(const GarmentRegions::Region& region, const MatrixX3i& faces,
                     const Eigen::Ref<const MatrixX3d>& V0, const Eigen::Ref<const MatrixX3d>& V1,
                     double clearance = 0.0);

}  // namespace gr
