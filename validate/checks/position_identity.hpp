#pragma once

#include <vector>

#include "core/common/types.hpp"

namespace gr {

/// Which rows of `vertices` (#V×3) are the same point: per row, the smallest row index
/// with identical coordinates (compared as numbers, so -0.0 equals 0.0). OBJ files write a
/// vertex once per UV seam side; those `v` lines are one point and the validator treats
/// them as one vertex when it decides which faces are neighbours.
std::vector<int> position_identity(const MatrixX3d& vertices);

}  // namespace gr
