#pragma once

#include <cstddef>
#include <limits>
#include <vector>

#include "core/common/types.hpp"

namespace gr {

/// A face of one mesh and a face of another (or the same) mesh.
struct FacePair {
  int first;
  int second;
};

inline bool operator==(const FacePair& a, const FacePair& b) {
  return a.first == b.first && a.second == b.second;
}
/// By first face, then second.
inline bool operator<(const FacePair& a, const FacePair& b) {
  return a.first != b.first ? a.first < b.first : a.second < b.second;
}

/// Intersecting face pairs: how many, and the first ones found (sorted).
struct FacePairList {
  std::size_t count = 0;
  std::vector<FacePair> pairs;  ///< at most the requested number
};

/// Every (face of `first`, face of `second`) pair that intersects or touches, decided with
/// exact predicates (CGAL's Exact_predicates_inexact_constructions_kernel) after a
/// box-intersection broad phase. A zero-area face is tested as the segment or point it is.
/// @param max_listed how many pairs to list; all are counted.
FacePairList find_intersecting_face_pairs(
    const TriangleMesh& first, const TriangleMesh& second,
    std::size_t max_listed = std::numeric_limits<std::size_t>::max());

}  // namespace gr
