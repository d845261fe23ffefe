#include "core/broad_phase/bvh.hpp"

#include <algorithm>
#include <numeric>

#include <tbb/parallel_invoke.h>

namespace gr {
namespace {

/// Subtrees at least this large build their two halves as parallel tasks.
constexpr int kParallelSubtree = 4096;

/// Nodes in the subtree over `count` primitives (the shape depends on the count only,
/// so each subtree's place in the flat array is known before it is built).
int subtree_nodes(int count) {
  if (count <= Bvh::kLeafSize) return 1;
  const int left = count / 2;
  return 1 + subtree_nodes(left) + subtree_nodes(count - left);
}

}  // namespace

void Bvh::build(std::vector<Eigen::AlignedBox3d> boxes) {
  const int n = static_cast<int>(boxes.size());
  ids_.resize(static_cast<std::size_t>(n));
  std::iota(ids_.begin(), ids_.end(), 0);
  boxes_ = std::move(boxes);
  nodes_.clear();
  if (n == 0) return;
  std::vector<Eigen::Vector3d> centres(static_cast<std::size_t>(n));
  for (std::size_t i = 0; i < centres.size(); ++i)
    centres[i] = boxes_[i].isEmpty() ? Eigen::Vector3d::Zero().eval() : boxes_[i].center().eval();
  nodes_.resize(static_cast<std::size_t>(subtree_nodes(n)));
  build_node(0, 0, n, centres);
  // Leaf boxes follow ids_ so a leaf's boxes are contiguous.
  std::vector<Eigen::AlignedBox3d> ordered(boxes_.size());
  for (std::size_t i = 0; i < ordered.size(); ++i) ordered[i] = boxes_[static_cast<std::size_t>(ids_[i])];
  boxes_ = std::move(ordered);
}

void Bvh::build_node(int node, int begin, int end, const std::vector<Eigen::Vector3d>& centres) {
  Node& out = nodes_[static_cast<std::size_t>(node)];
  const int count = end - begin;
  if (count <= kLeafSize) {
    out.first = begin;
    out.count = count;
    out.box.setEmpty();
    for (int i = begin; i < end; ++i) out.box.extend(boxes_[static_cast<std::size_t>(ids_[static_cast<std::size_t>(i)])]);
    return;
  }
  Eigen::AlignedBox3d centre_box;
  for (int i = begin; i < end; ++i) centre_box.extend(centres[static_cast<std::size_t>(ids_[static_cast<std::size_t>(i)])]);
  int axis;
  centre_box.sizes().maxCoeff(&axis);
  const int middle = begin + count / 2;
  std::nth_element(ids_.begin() + begin, ids_.begin() + middle, ids_.begin() + end,
                   [&](int a, int b) {
                     return centres[static_cast<std::size_t>(a)][axis] < centres[static_cast<std::size_t>(b)][axis];
                   });
  const int left = node + 1;
  const int right = left + subtree_nodes(middle - begin);
  if (count >= kParallelSubtree) {
    tbb::parallel_invoke([&] { build_node(left, begin, middle, centres); },
                         [&] { build_node(right, middle, end, centres); });
  } else {
    build_node(left, begin, middle, centres);
    build_node(right, middle, end, centres);
  }
  out.first = right;
  out.count = 0;
  out.box = nodes_[static_cast<std::size_t>(left)].box.merged(nodes_[static_cast<std::size_t>(right)].box);
}

}  // namespace gr
