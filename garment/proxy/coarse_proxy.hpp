#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/inflation/garment_problem.hpp"

namespace gr {

/// Each vertex of a fine mesh as a point of a coarse surface: the coarse face nearest it
/// at rest, its barycentric coordinates there, and its offset from that point in the
/// face's own frame (first edge, normal, and their cross product), so that it follows the
/// face as the coarse mesh moves and turns.
class SurfaceEmbedding {
 public:
  SurfaceEmbedding() = default;
  /// Each fine vertex lies on a face of its own piece (a garment's vertices never follow
  /// another garment's faces), or on the nearest face when its piece has none.
  /// @param coarse the coarse mesh at rest (#Vc×3, #Fc×3), in the fine mesh's frame.
  /// @param fine_vertices #Vf×3.
  /// @param coarse_vertex_piece, fine_vertex_piece per vertex, its piece (any ids common to
  ///        both); empty: one piece.
  /// @pre coarse has at least one face.
  SurfaceEmbedding(const TriangleMesh& coarse, const MatrixX3d& fine_vertices,
                   const std::vector<int>& coarse_vertex_piece = {},
                   const std::vector<int>& fine_vertex_piece = {});

  /// The fine vertices (#Vf×3) where the coarse mesh has `coarse_vertices` (#Vc×3, the
  /// rest's connectivity); at rest, the fine vertices again (to rounding). A coarse face
  /// that degenerates carries its points without their offsets.
  MatrixX3d carry(const Eigen::Ref<const MatrixX3d>& coarse_vertices) const;
  /// The largest distance of a fine vertex from the coarse surface at rest.
  double max_offset() const { return max_offset_; }

 private:
  struct Placement {
    int face = 0;
    Vector3d barycentric = Vector3d::Zero();
    Vector3d offset = Vector3d::Zero();  ///< along (first edge, normal × first edge, normal)
  };
  MatrixX3i faces_;
  std::vector<Placement> placements_;

  double max_offset_ = 0.0;
};

/// A coarse stand-in for a dense garment (coarse to fine): the same scene with the garment
/// decimated to about `target_faces` faces, and where the garment's vertices sit on it.
struct CoarseProxy {
  GarmentScene scene;            ///< the fine scene with the decimated garment
  SurfaceEmbedding embedding;    ///< the fine garment's vertices on the proxy
  std::vector<int> fine_vertex;  ///< per proxy vertex, the nearest fine vertex at rest
  /// How much further than the garment the proxy should keep from the avatar, so that the
  /// garment carried with it stays clear too (normalized units): the garment's largest
  /// distance from it at rest, plus the depth by which a garment edge across a bent proxy
  /// edge cuts inside it.
  double clearance = 0.0;
  /// The proxy's median edge length (normalized units): the finest detail its paths show.
  double edge_length = 0.0;
};

/// The proxy of `fine` (normalized units), or why there is none (`why_not` set): the
/// garment carries data the proxy cannot stand for (ties, attachments, tangles, faces
/// out of the avatar contact), CGAL's decimation cannot read it as a surface, or the
/// decimated garment is degenerate or crosses the shrunk avatar or itself (exact test),
/// which the barrier solve must never start from. Each piece (a layer of an outfit, a
/// pocket) is decimated on its own by the same ratio, and carries only its own garment
/// vertices. Per-vertex data (no-fit, fit offsets, skirt vertices) is the nearest fine
/// vertex's of the same piece.
/// @pre target_faces > 0.
std::optional<CoarseProxy> make_coarse_proxy(const GarmentScene& fine, int target_faces,
                                             std::string& why_not);

}  // namespace gr
