#include "validate/checks/broad_phase.hpp"

#include <algorithm>

#include <CGAL/box_intersection_d.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace gr {

namespace {

using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, int>;

std::vector<Box> make_boxes(const TriangleMesh& mesh) {
  std::vector<Box> boxes;
  boxes.reserve(static_cast<std::size_t>(mesh.faces.rows()));
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    double lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
      lo[k] = hi[k] = mesh.vertices(mesh.faces(f, 0), k);
      for (int c = 1; c < 3; ++c) {
        lo[k] = std::min(lo[k], mesh.vertices(mesh.faces(f, c), k));
        hi[k] = std::max(hi[k], mesh.vertices(mesh.faces(f, c), k));
      }
    }
    boxes.emplace_back(lo, hi, static_cast<int>(f));
  }
  return boxes;
}

}  // namespace

std::vector<FacePair> overlapping_face_boxes(const TriangleMesh& first,
                                             const TriangleMesh& second) {
  std::vector<Box> first_boxes = make_boxes(first);
  std::vector<Box> second_boxes = make_boxes(second);
  std::vector<FacePair> overlapping;
  // Closed boxes (the default topology): touching boxes are reported.
  CGAL::box_intersection_d(first_boxes.begin(), first_boxes.end(), second_boxes.begin(),
                           second_boxes.end(), [&](const Box& a, const Box& b) {
                             overlapping.push_back({a.info(), b.info()});
                           });
  return overlapping;
}

std::vector<FacePair> overlapping_face_boxes(const TriangleMesh& mesh) {
  std::vector<Box> boxes = make_boxes(mesh);
  std::vector<FacePair> overlapping;
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& a, const Box& b) {
    overlapping.push_back({std::min(a.info(), b.info()), std::max(a.info(), b.info())});
  });
  return overlapping;
}

FacePairList keep_intersecting(const std::vector<FacePair>& candidates,
                               const std::function<bool(const FacePair&)>& intersects,
                               std::size_t max_listed) {
  std::vector<char> hit(candidates.size(), 0);
  // Blocks of kGrain candidates: a short list (one moved region's pairs, checked thousands
  // of times by the untangle) stays on the calling thread instead of waking the others.
  constexpr std::size_t kGrain = 1024;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, candidates.size(), kGrain),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i)
                        hit[i] = intersects(candidates[i]) ? 1 : 0;
                    });
  FacePairList result;
  for (std::size_t i = 0; i < candidates.size(); ++i)
    if (hit[i]) result.pairs.push_back(candidates[i]);
  std::sort(result.pairs.begin(), result.pairs.end(), [](const FacePair& a, const FacePair& b) {
    return a.first != b.first ? a.first < b.first : a.second < b.second;
  });
  result.count = result.pairs.size();
  if (result.pairs.size() > max_listed) result.pairs.resize(max_listed);
  return result;
}

}  // namespace gr
