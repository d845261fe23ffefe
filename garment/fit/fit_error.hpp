#pragma once

#include <vector>

#include "core/common/types.hpp"

namespace gr {

/// How close the fitted garment sits to the avatar: unsigned distances from sample points
/// of the fit faces (centroid and the three points halfway between centroid and corners;
/// the same rule for every preset so runs compare) to the avatar surface.
struct FitError {
  double mean = 0.0;
  double p95 = 0.0;
  std::size_t samples = 0;
};

/// @param fit_faces per garment face, true when it should fit (not no-fit).
/// Distances in the units of the inputs.
FitError measure_fit_error(const TriangleMesh& garment, const std::vector<bool>& fit_faces,
                           const TriangleMesh& avatar);

}  // namespace gr
