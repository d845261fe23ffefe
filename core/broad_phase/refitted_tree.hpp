#pragma once

#include <vector>

#include <Eigen/Geometry>

#include "core/broad_phase/bvh.hpp"

namespace gr {

/// A Bvh kept over boxes that move a little between queries: refitted to each new set of
/// boxes, and rebuilt only when a refit has loosened it by more than kMaxLoosening over its
/// looseness when built (or when the box count changes).
struct RefittedTree {
  static constexpr double kMaxLoosening = 1.25;
  Bvh tree;
  double built_looseness = 0.0;  ///< tree.looseness() right after the last build

  /// Gives the tree `boxes` (primitive i gets boxes[i]), by refit or rebuild as above.
  void update(std::vector<Eigen::AlignedBox3d> boxes);
};

}  // namespace gr
