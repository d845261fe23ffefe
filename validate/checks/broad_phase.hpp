#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "core/common/types.hpp"
#include "validate/checks/mesh_intersections.hpp"

namespace gr {

/// Face pairs whose closed bounding boxes overlap (CGAL box_intersection_d), so faces that
/// only touch reach the exact test. Boxes are the corners' exact coordinate ranges.
/// @return (face of first, face of second) pairs, in no particular order.
std::vector<FacePair> overlapping_face_boxes(const TriangleMesh& first, const TriangleMesh& second);

/// Pairs of distinct faces of one mesh whose closed bounding boxes overlap, each pair once
/// with first < second.
std::vector<FacePair> overlapping_face_boxes(const TriangleMesh& mesh);

/// The candidates for which `intersects` holds (evaluated in parallel, so it must be safe
/// to call concurrently), sorted by (first, second), all counted and the first
/// `max_listed` listed.
FacePairList keep_intersecting(const std::vector<FacePair>& candidates,
                               const std::function<bool(const FacePair&)>& intersects,
                               std::size_t max_listed);

}  // namespace gr
