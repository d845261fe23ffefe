#pragma once

#include <vector>

#include "core/common/types.hpp"

namespace gr {

/// Avatar faces the garment can reach while the avatar inflates from A0 to A: those whose
/// box over the whole motion meets the garment's box grown by `margin` (normalized
/// units). The garment moves mostly where the avatar pushes it (about the largest avatar
/// displacement) or the fit pulls it (about the fit band), so a margin of the two plus
/// dhat is usually enough; within_contact_scope tells when it was not. Faces further away (the head
/// over a skirt, the feet under a jacket) stay out of the contact problem; the certificate still
/// checks every face.
/// @param shrunk, target #Va×3 avatar positions at t = 0 and t = 1; faces #Fa×3.
/// @return row indices into faces, ascending.
std::vector<int> reachable_avatar_faces(const Eigen::Ref<const MatrixX3d>& garment,
                                        const Eigen::Ref<const MatrixX3d>& shrunk,
                                        const Eigen::Ref<const MatrixX3d>& target,
                                        const Eigen::Ref<const MatrixX3i>& faces, double margin);

/// Whether `garment` (#Vg×3) still lies where reachable_avatar_faces(`start`, ..., margin)
/// modelled every avatar face it can touch: inside the box of `start` grown by
/// margin − dhat, beyond which an unmodelled face could come within the barrier's reach.
/// The margin is an estimate of how far a solve moves the garment, not a bound: a caller
/// that finds the garment outside solves again with every avatar face.
bool within_contact_scope(const Eigen::Ref<const MatrixX3d>& start,
                          const Eigen::Ref<const MatrixX3d>& garment, double margin, double dhat);

}  // namespace gr
