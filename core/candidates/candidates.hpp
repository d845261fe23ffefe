#pragma once

#include <array>
#include <memory>
#include <vector>

#include <Eigen/Geometry>

#include "core/candidates/contact_mesh.hpp"
#include "core/candidates/fold_free_regions.hpp"

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

/// Keys that name a self pair whatever the order of its vertices: {0, point, triangle
/// sorted} and {1, the two edges, each sorted, the smaller first}.
std::array<int, 5> self_pair_key(const PointTriangleCandidate& pair);
std::array<int, 5> self_pair_key(const EdgeEdgeCandidate& pair);

class SelfContactSearch;

/// Finds candidates (as find_candidates and find_swept_candidates below) for one contact
/// mesh over many calls, keeping what stays valid between them:
/// - the avatar's trees are reused while the avatar's vertex boxes and the radius are
///   unchanged (in the fit the avatar does not move);
/// - the garment's trees are refitted to each query's boxes, and rebuilt only when that
///   has loosened them by a quarter over their state when built;
/// - a static query whose vertices all lie on the last swept query's motion (each on its
///   segment, up to rounding; at no larger radius) filters that query's pairs instead of
///   searching again: a pair close at such a point is close somewhere along the motion, so
///   the swept list holds it. An accepted line-search point lies on the swept motion, so
///   each Newton step searches the trees once.
/// - pairs whose boxes overlap but whose separation bound (pair_separation.hpp) rules them
///   out are dropped before they reach the narrow phase.
/// - self pairs are searched region against region by a SelfContactSearch
///   (self_contact_search.hpp, made from the garment of the first query); with
///   mesh.cull_fold_free, pairs inside a region, or across the seam of two neighbouring
///   leaves, that `stays_fold_free` along the query's motion (clearing the query's radius)
///   are left out: they cannot touch, nor come that close.
/// The lists keep the order of the search they come from, the same on any thread count.
/// Not safe for concurrent use.
class CandidateFinder {
 public:
  explicit CandidateFinder(ContactMesh mesh);
  ~CandidateFinder();
  CandidateFinder(const CandidateFinder&) = delete;
  CandidateFinder& operator=(const CandidateFinder&) = delete;

  const ContactMesh& mesh() const { return mesh_; }
  /// The garment's regions (null before the first query with self contact).
  const GarmentRegions* regions() const;
  /// Per region, whether the last search left its inside out as fold free.
  const std::vector<char>& fold_free() const;
  /// Mean, over swept queries so far, of the fraction of garment faces whose self pairs
  /// were left out as fold free (0 before any).
  double mean_fold_free_fraction() const {
    return swept_queries_ > 0 ? fold_free_fraction_sum_ / static_cast<double>(swept_queries_) : 0.0;
  }
  /// As find_candidates. @throw std::invalid_argument when V has the wrong row count.
  Candidates find(const Eigen::Ref<const MatrixX3d>& V, double inflation_radius);
  /// As find_swept_candidates. @throw std::invalid_argument for a wrong row count.
  Candidates find_swept(const Eigen::Ref<const MatrixX3d>& V0,
                        const Eigen::Ref<const MatrixX3d>& V1, double inflation_radius);

 private:
  struct AvatarTrees;
  struct GarmentTrees;
  using Box = Eigen::AlignedBox3d;

  void check_positions(const Eigen::Ref<const MatrixX3d>& V) const;
  /// Pairs whose element boxes (vertex boxes grown by radius / 2) overlap and whose
  /// separation bound over V0 → V1 is below `threshold`.
  Candidates box_pairs(const std::vector<Box>& vertex_boxes, double radius,
                       const Eigen::Ref<const MatrixX3d>& V0, const Eigen::Ref<const MatrixX3d>& V1,
                       double threshold);
  /// Whether every vertex of V lies on its segment of the last swept motion.
  bool on_swept_motion(const Eigen::Ref<const MatrixX3d>& V) const;
  Candidates filter_swept(const Eigen::Ref<const MatrixX3d>& V, double radius) const;

  ContactMesh mesh_;
  std::unique_ptr<SelfContactSearch> self_;  ///< made at the first query with self contact
  long swept_queries_ = 0;
  double fold_free_fraction_sum_ = 0.0;
  std::vector<int> avatar_points_;  ///< avatar vertices that some contact face uses
  std::unique_ptr<AvatarTrees> avatar_trees_;
  std::unique_ptr<GarmentTrees> garment_trees_;
  Candidates swept_;                   ///< the last swept query's pairs
  MatrixX3d swept_start_, swept_end_;  ///< and its motion
  double swept_radius_ = -1.0;
};

/// Every pair whose distance at `V` may be below `inflation_radius` (a superset: pairs
/// whose bounding boxes come within the radius and whose separation bound,
/// core/broad_phase/pair_separation.hpp, is below it). Built from bounding volume hierarchies
/// rebuilt on every call (core/broad_phase/bvh.hpp); the order of the lists is fixed by
/// the geometry, the same on any thread count.
/// @param V stacked positions, #(garment+avatar)×3, in normalized scene units.
/// @throw std::invalid_argument when V's row count is not mesh.vertex_count().
Candidates find_candidates(const ContactMesh& mesh, const Eigen::Ref<const MatrixX3d>& V,
                           double inflation_radius);

/// Every pair whose swept volumes along the linear motion V0 → V1 come within
/// `inflation_radius` of each other (a superset of the pairs that CCD must check): each
/// vertex's box spans its start and end positions, and the separation bound over the
/// motion is below the radius.
/// @throw std::invalid_argument when V0 or V1 has the wrong row count.
Candidates find_swept_candidates(const ContactMesh& mesh, const Eigen::Ref<const MatrixX3d>& V0,
                                 const Eigen::Ref<const MatrixX3d>& V1, double inflation_radius);

/// The self pairs (sharing no vertex, all of their vertices in one tangle of
/// mesh.garment_tangles) closer than `gap` at the garment positions `garment`
/// (#garment vertices×3): sorted self_pair_key values, for ContactMesh::
/// unmodelled_self_pairs.
std::vector<std::array<int, 5>> tangled_pairs_closer_than(
    const ContactMesh& mesh, const Eigen::Ref<const MatrixX3d>& garment, double gap);

/// The self pairs (sharing no vertex) closer than `gap` at the garment positions `garment`
/// (#garment vertices×3) every face pair of which is listed in
/// mesh.garment_crossing_faces: for a point and a triangle, each face holding the point
/// with the triangle's face; for two edges, each face holding one with each face holding
/// the other. Leaving out only these keeps every face pair that does not cross fully
/// modelled. Vertices tied in one place (`same_place`, pairs of garment vertices such as a
/// split edge's copy and its original) count as one: pairs that hold both sides of a tie
/// touch as neighbours do and are left out too. Sorted self_pair_key values, for
/// ContactMesh::unmodelled_self_pairs.
std::vector<std::array<int, 5>> crossing_pairs_closer_than(
    const ContactMesh& mesh, const Eigen::Ref<const MatrixX3d>& garment, double gap,
    const std::vector<std::array<int, 2>>& same_place = {});

}  // namespace gr
