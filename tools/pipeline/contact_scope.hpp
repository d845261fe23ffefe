#pragma once

#include <vector>

#include "core/common/types.hpp"

namespace gr {

/// Avatar faces the garment can reach while the avatar inflates from A0 to A: those whose
/// box over the whole motion meets the garment's box grown by `margin` (normalized
/// units). The garment moves only where the avatar pushes it (at most the largest avatar
/// displacement) or the fit pulls it (at most the fit band), so a margin of the two plus
/// dhat is enough. Faces further away (the head over a skirt, the feet under a jacket)
/// stay out of the contact problem; the certificate still checks every face.
/// @param shrunk, target #Va×3 avatar positions at t = 0 and t = 1; faces #Fa×3.
/// @return row indices into faces, ascending.
std::vector<int> reachable_avatar_faces(const Eigen::Ref<const MatrixX3d>& garment,
                                        const Eigen::Ref<const MatrixX3d>& shrunk,
                                        const Eigen::Ref<const MatrixX3d>& target,
                                        const Eigen::Ref<const MatrixX3i>& faces, double margin);

}  // namespace gr
