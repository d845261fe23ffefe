#pragma once

#include "core/common/types.hpp"

namespace gr {

/// When a garment vertex may take the body's weights at its closest body point directly.
struct SkinTransferOptions {
  /// Largest distance to the closest body point, as a fraction of the body's
  /// bounding-box diagonal.
  double max_distance = 0.05;
  /// Largest angle between the garment vertex normal and the body normal there (degrees).
  double max_angle_degrees = 30.0;
  /// Joints kept per vertex (the largest weights, renormalized).
  int max_influences = 4;
};

/// Skin weights transferred from a body to a garment (#Vg×#J, rows non-negative, summing
/// to 1, at most max_influences non-zero), with how each vertex got them.
struct SkinTransferResult {
  Eigen::MatrixXd weights;
  int matched = 0;    ///< vertices that took the body's weights at their closest point
  int inpainted = 0;  ///< vertices whose weights the Laplacian solve filled in
  int unreached = 0;  ///< of the matched: in a part with no match, taken without thresholds
  double seconds = 0.0;
};

/// Transfers skin weights from `body` to `garment` (both in the same frame and units):
/// a garment vertex whose closest body point is within the distance threshold and whose
/// normal agrees with the body's there within the angle threshold takes the body's
/// interpolated weights; the others are inpainted by minimising the smoothness energy
/// w^T (-L + L M^-1 L) w over the garment (cotangent Laplacian L, lumped mass M scaled to
/// mean 1 so the energy does not depend on the mesh's units) with the matched weights
/// fixed, one sparse Cholesky factorization (CHOLMOD) for every joint. A connected part of
/// the garment with no matched vertex takes every vertex's closest-point weights.
/// Negative results are clamped, then each vertex keeps its `max_influences` largest
/// weights, renormalized to sum 1.
/// @param body_weights #Vb×#J, non-negative; a row summing to 0 counts as unskinned.
/// @pre body has at least one face; vertex normals of both meshes follow the right-hand
///      rule of their faces.
/// @throw std::invalid_argument on mismatched sizes or an options value out of range.
SkinTransferResult transfer_skin_weights(const TriangleMesh& body,
                                         const Eigen::Ref<const Eigen::MatrixXd>& body_weights,
                                         const TriangleMesh& garment,
                                         const SkinTransferOptions& options);

}  // namespace gr
