#include "core/broad_phase/bvh.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <stdexcept>

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

/// The 10 low bits of v spread to every third bit.
std::uint32_t spread_bits(std::uint32_t v) {
  v &= 0x3ffu;
  v = (v | (v << 16)) & 0x030000ffu;
  v = (v | (v << 8)) & 0x0300f00fu;
  v = (v | (v << 4)) & 0x030c30c3u;
  v = (v | (v << 2)) & 0x09249249u;
  return v;
}

/// Sorts 64-bit keys by their high 32 bits (stable: equal codes keep their order), least
/// significant digit first, 11 bits per pass.
void radix_sort_high_half(std::vector<std::uint64_t>& keys) {
  std::vector<std::uint64_t> buffer(keys.size());
  for (int shift = 32; shift < 64; shift += 11) {
    std::size_t counts[2049] = {};
    for (const std::uint64_t key : keys) ++counts[((key >> shift) & 0x7ffu) + 1];
    for (std::size_t d = 0; d < 2048; ++d) counts[d + 1] += counts[d];
    for (const std::uint64_t key : keys) buffer[counts[(key >> shift) & 0x7ffu]++] = key;
    keys.swap(buffer);
  }
}

}  // namespace

Bvh::FloatBox Bvh::FloatBox::outward(const Eigen::AlignedBox3d& box) {
  FloatBox out;
  if (box.isEmpty()) {
    out.min.setConstant(std::numeric_limits<float>::infinity());
    out.max.setConstant(-std::numeric_limits<float>::infinity());
    return out;
  }
  // Rounding to float moves a value by at most |x| 2^-24; widening by |x| 2^-22 first
  // (plus a tiny absolute amount near zero) keeps the float box around the double one.
  const Eigen::Array3d lo = box.min().array(), hi = box.max().array();
  const Eigen::Array3d slack_lo = lo.abs() * 0x1p-22 + 1e-30, slack_hi = hi.abs() * 0x1p-22 + 1e-30;
  out.min << (lo - slack_lo).cast<float>(), 0.0f;
  out.max << (hi + slack_hi).cast<float>(), 0.0f;
  return out;
}

void Bvh::build(std::vector<Eigen::AlignedBox3d> boxes) {
  const auto n = boxes.size();
  nodes_.clear();
  ids_.clear();
  boxes_.clear();
  if (n == 0) return;
  // Morton code of each box centre in the centres' bounding box, 10 bits per axis, as the
  // high half of a key whose low half is the id: one integer sort orders the leaves.
  std::vector<Eigen::Vector3d> centres(n);
  Eigen::AlignedBox3d centre_box;
  for (std::size_t i = 0; i < n; ++i) {
    centres[i] = boxes[i].isEmpty() ? Eigen::Vector3d::Zero().eval() : boxes[i].center().eval();
    centre_box.extend(centres[i]);
  }
  const Eigen::Array3d scale = 1023.0 / centre_box.sizes().array().max(1e-300);
  std::vector<std::uint64_t> keys(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Array3d cell = ((centres[i] - centre_box.min()).array() * scale).min(1023.0);
    const std::uint32_t code = spread_bits(static_cast<std::uint32_t>(cell.x())) << 2 |
                               spread_bits(static_cast<std::uint32_t>(cell.y())) << 1 |
                               spread_bits(static_cast<std::uint32_t>(cell.z()));
    keys[i] = std::uint64_t{code} << 32 | i;
  }
  radix_sort_high_half(keys);
  ids_.resize(n);
  boxes_.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    ids_[k] = static_cast<int>(keys[k] & 0xffffffffu);
    boxes_[k] = FloatBox::outward(boxes[static_cast<std::size_t>(ids_[k])]);
  }
  nodes_.resize(static_cast<std::size_t>(subtree_nodes(static_cast<int>(n))));
  build_node(0, 0, static_cast<int>(n));
}

void Bvh::refit(const std::vector<Eigen::AlignedBox3d>& boxes) {
  if (boxes.size() != ids_.size())
    throw std::invalid_argument("a refit needs one box per primitive of the tree");
  for (std::size_t k = 0; k < ids_.size(); ++k)
    boxes_[k] = FloatBox::outward(boxes[static_cast<std::size_t>(ids_[k])]);
  // Children come after their parent in the flat array: one backward sweep.
  for (std::size_t n = nodes_.size(); n-- > 0;) {
    Node& node = nodes_[n];
    if (node.count > 0) {
      node.box = boxes_[static_cast<std::size_t>(node.first)];
      for (int i = node.first + 1; i < node.first + node.count; ++i)
        node.box.extend(boxes_[static_cast<std::size_t>(i)]);
    } else {
      node.box = nodes_[n + 1].box;
      node.box.extend(nodes_[static_cast<std::size_t>(node.first)].box);
    }
  }
}

double Bvh::looseness() const {
  double nodes = 0.0, primitives = 0.0;
  for (const Node& node : nodes_) nodes += node.box.half_perimeter();
  for (const FloatBox& box : boxes_) primitives += box.half_perimeter();
  return primitives > 0.0 ? nodes / primitives : 1.0;
}

void Bvh::build_node(int node, int begin, int end) {
  Node& out = nodes_[static_cast<std::size_t>(node)];
  const int count = end - begin;
  if (count <= kLeafSize) {
    out.first = begin;
    out.count = count;
    out.box = boxes_[static_cast<std::size_t>(begin)];
    for (int i = begin + 1; i < end; ++i) out.box.extend(boxes_[static_cast<std::size_t>(i)]);
    return;
  }
  const int middle = begin + count / 2;
  const int left = node + 1;
  const int right = left + subtree_nodes(middle - begin);
  if (count >= kParallelSubtree) {
    tbb::parallel_invoke([&] { build_node(left, begin, middle); },
                         [&] { build_node(right, middle, end); });
  } else {
    build_node(left, begin, middle);
    build_node(right, middle, end);
  }
  out.first = right;
  out.count = 0;
  out.box = nodes_[static_cast<std::size_t>(left)].box;
  out.box.extend(nodes_[static_cast<std::size_t>(right)].box);
}

}  // namespace gr
