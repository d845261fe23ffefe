#pragma once

#include <cstddef>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "core/broad_phase/refitted_tree.hpp"
#include "core/candidates/candidates.hpp"
#include "core/candidates/contact_mesh.hpp"
#include "core/candidates/fold_free_regions.hpp"

namespace gr {

/// The garment's self-contact pairs for CandidateFinder, searched region against region
/// over the garment's region hierarchy (fold_free_regions.hpp), which is made once, from
/// the positions given at construction. Each leaf keeps refitted trees (RefittedTree) over
/// the points, faces and edges it owns; one more group holds the points no face uses.
/// With mesh.cull_fold_free, pairs inside a region, or across the seam of two neighbouring
/// leaves, that `stays_fold_free` along the query's motion (clearing the query's
/// threshold) are left out: they cannot touch, nor come that close. The pairs come in an
/// order fixed by the hierarchy, the same on any thread count. Not safe for concurrent use.
class SelfContactSearch {
 public:
  /// @param mesh the contact mesh (kept by reference: it must outlive the search).
  /// @param garment #Vg×3 garment positions the regions are built from (normalized units).
  SelfContactSearch(const ContactMesh& mesh, const Eigen::Ref<const MatrixX3d>& garment);

  /// Appends to the lists every garment–garment pair that shares no vertex, whose boxes
  /// overlap and whose separation bound over V0 → V1 (pair_separation.hpp) is below
  /// `threshold`, except pairs left out as fold free; records each region's verdict.
  /// @param point_boxes #Vg, @param face_boxes #Fg, @param edge_boxes #Eg boxes of the
  ///        garment's vertices, faces and edges (already grown by half the search radius).
  /// @param V0 and @param V1 stacked positions (#(garment+avatar)×3), the same matrix for
  ///        a search without motion.
  void find(const std::vector<Eigen::AlignedBox3d>& point_boxes,
            const std::vector<Eigen::AlignedBox3d>& face_boxes,
            const std::vector<Eigen::AlignedBox3d>& edge_boxes,
            const Eigen::Ref<const MatrixX3d>& V0, const Eigen::Ref<const MatrixX3d>& V1,
            double threshold, std::vector<PointTriangleCandidate>& point_triangle,
            std::vector<EdgeEdgeCandidate>& edge_edge);

  const GarmentRegions& regions() const { return regions_; }
  /// Per region, whether the last search left its inside out as fold free.
  const std::vector<char>& fold_free() const { return fold_free_; }
  /// Garment faces inside regions the last search left out as fold free.
  std::size_t fold_free_faces() const { return fold_free_faces_; }

 private:
  using Box = Eigen::AlignedBox3d;

  /// Marks fold-free regions top-down (a region found fold free is not split further).
  void mark_fold_free(int region, const Eigen::Ref<const MatrixX3d>& V0,
                      const Eigen::Ref<const MatrixX3d>& V1, double clearance);
  /// Leaf pairs to search for pairs between regions a and b (boxes permitting).
  void cross(int a, int b, std::vector<std::pair<int, int>>& tasks) const;
  /// Leaf pairs to search within region r: none when it is fold free.
  void within(int r, std::vector<std::pair<int, int>>& tasks) const;

  const ContactMesh& mesh_;
  GarmentRegions regions_;
  std::vector<std::vector<int>> points_, edges_;  ///< per group, ids it owns
  std::vector<RefittedTree> point_trees_, face_trees_, edge_trees_;
  std::vector<char> fold_free_;  ///< per region, the last query's verdict
  std::vector<Box> extent_;      ///< per region, the last query's box
  std::size_t fold_free_faces_ = 0;
};

}  // namespace gr
