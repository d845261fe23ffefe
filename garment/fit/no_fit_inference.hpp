#pragma once

#include <string>
#include <vector>

#include "core/common/types.hpp"
#include "core/io/rig_files.hpp"

namespace gr {

/// The rules that infer which garment parts hang free. Lengths are relative (to the
/// garment's edges or the skeleton's bones), so they hold in any units.
struct NoFitOptions {
  /// Source body rule: a vertex is loose when its distance to the source body exceeds the
  /// garment's snug offset by more than this many of its own mean edge lengths.
  double body_distance_edges = 0.8;
  /// The snug offset: this percentile (0 to 100) of the garment's vertex distances to the
  /// source body, how far its closest-fitting parts sit off it (a padded jacket's lining).
  double snug_percentile = 5.0;
  /// Loose regions (connected over garment edges) hang free when they reach a boundary loop
  /// (a hem, a collar: free parts hang from the fitted ones) and hold at least this share of
  /// the garment's vertices; fitted regions that reach no boundary loop, enclosed by free
  /// ones, hang free with them.
  double min_region_share = 0.01;
  /// Skirt rule (a skirt's vertices): free below the plane across the legs this many thigh
  /// lengths (hip to knee) above the hip joints.
  double hip_offset = 0.05;
  /// End joint rule: free beyond an end joint (the last joint of a limb, or the neck, see
  /// BindingOptions::end_angle_degrees) less this many lengths of its bone, for the
  /// vertices nearest that bone, the segment beyond it or another bone leaving the joint it
  /// leaves (the collar above the neck, where it meets the shoulders).
  /// Applied when there is no source body; negative switches it off.
  double end_margin = 0.1;
  /// Which joint is the skeleton's root, and when a joint ends a chain (see BindingOptions).
  int root_joint = 0;
  double end_angle_degrees = 135.0;
};

/// The inferred no-fit list and the rules that made it.
struct NoFitInference {
  std::vector<int> vertices;  ///< sorted garment vertex ids (rows of the garment given)
  std::string method;         ///< the rules applied, e.g. "source body distance, skirt hips"
  int from_body = 0;          ///< free vertices from each rule (a vertex may count twice)
  int from_hips = 0;
  int from_end_joints = 0;
  /// Source body rule: the snug offset, in the garment's units (0 without a body).
  double snug_offset = 0.0;
};

/// Infers which parts of a garment hang free rather than fit, in the garment's frame:
/// from the body it was made on when there is one (loose regions reaching a boundary
/// loop), below the hips for a skirt, and else beyond the skeleton's end joints. A face
/// hangs free when its three vertices are listed, as for a hand-made list.
/// @param garment #Vg×3 / #Fg×3, welded.
/// @param source_body the body the garment was made on, same frame, or nullptr.
/// @param source_skeleton the garment's skeleton, same frame, or nullptr (no skirt or end
///        joint rule then).
/// @param skirt_vertices per garment vertex, 1 for a skirt's: the skirt rule applies to
///        those (needs the skeleton); empty: to none.
/// @throw std::invalid_argument when an option is out of range (percentile outside
///        [0, 100], a negative edge count or share, a root joint out of range); InputError from
///        find_leg_joints when a vertex is a skirt's and the skeleton has no legs.
NoFitInference infer_no_fit(const TriangleMesh& garment, const TriangleMesh* source_body,
                            const Skeleton* source_skeleton,
                            const std::vector<char>& skirt_vertices,
                            const NoFitOptions& options = {});

/// Intersection over union of two no-fit lists, on the faces they leave free (all three
/// vertices listed); 1 when both leave none.
double no_fit_face_iou(const MatrixX3i& faces, int vertex_count, const std::vector<int>& a,
                       const std::vector<int>& b);

}  // namespace gr
