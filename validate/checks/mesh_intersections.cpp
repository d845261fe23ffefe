#include "validate/checks/mesh_intersections.hpp"

#include "validate/checks/broad_phase.hpp"
#include "validate/checks/exact_simplex.hpp"

namespace gr {

FacePairList find_intersecting_face_pairs(const TriangleMesh& first, const TriangleMesh& second,
                                          std::size_t max_listed) {
  const std::vector<exact::Simplex> first_simplices = exact::make_simplices(first);
  const std::vector<exact::Simplex> second_simplices = exact::make_simplices(second);
  return keep_intersecting(
      overlapping_face_boxes(first, second),
      [&](const FacePair& pair) {
        return exact::simplices_intersect(first_simplices[static_cast<std::size_t>(pair.first)],
                                          second_simplices[static_cast<std::size_t>(pair.second)]);
      },
      max_listed);
}

}  // namespace gr
