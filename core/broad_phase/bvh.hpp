#pragma once

#include <utility>
#include <vector>

#include <tbb/parallel_for.h>

#include <Eigen/Geometry>

namespace gr {

/// A binary bounding volume hierarchy over axis-aligned boxes. Built by sorting the box
/// centres along a Morton (Z-order) curve and halving the sorted range, at most kLeafSize
/// boxes per leaf, nodes in one flat array: O(n log n) for the sort, O(n) for the rest.
/// Queries: one box against the tree, or every intersecting pair between two trees (or
/// within one) by descending both at once, in parallel and in an order fixed by the trees,
/// so results do not depend on the thread count. Boxes are closed: touching counts.
/// Boxes are stored in single precision rounded outward (4-wide compares), so a query
/// returns every box that truly intersects, and at worst a few that miss by one float ulp.
class Bvh {
 public:
  static constexpr int kLeafSize = 4;

  /// Builds over `boxes`; primitive ids are their indices.
  void build(std::vector<Eigen::AlignedBox3d> boxes);

  /// Number of primitives.
  int size() const { return static_cast<int>(ids_.size()); }

  /// Gives primitive i the box boxes[i] (same count as built) and updates the node boxes
  /// bottom-up, keeping the tree's shape: O(n), and queries stay exact. Their cost grows
  /// as the primitives move away from the layout the tree was built for (see looseness).
  /// @throw std::invalid_argument when the count differs from the tree's.
  void refit(const std::vector<Eigen::AlignedBox3d>& boxes);
  /// Sum of the node boxes' half perimeters over the primitives' (at least 1 for a
  /// non-empty tree): how much space the descent wades through per primitive. A refitted
  /// tree whose looseness has grown well past its value at build time is worth rebuilding.
  double looseness() const;

  /// Calls `visit(id)` once for every primitive whose box intersects `query`.
  template <typename Visit>
  void query(const Eigen::AlignedBox3d& query_box, Visit&& visit) const {
    if (nodes_.empty()) return;
    const FloatBox query = FloatBox::outward(query_box);
    int stack[kMaxDepth];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const int n = stack[--top];
      const Node& node = nodes_[static_cast<std::size_t>(n)];
      if (!node.box.intersects(query)) continue;
      if (node.count > 0) {
        for (int i = node.first; i < node.first + node.count; ++i)
          if (boxes_[static_cast<std::size_t>(i)].intersects(query))
            visit(ids_[static_cast<std::size_t>(i)]);
      } else {
        stack[top++] = node.first;
        stack[top++] = n + 1;
      }
    }
  }

  /// Every pair (a primitive of this tree, a primitive of `other`) whose boxes intersect,
  /// passed to `emit(id, other_id, sink)` with `sink` a std::vector<T> the caller fills;
  /// the sinks are joined in a fixed order into the result. With `other` == this, each
  /// unordered pair of distinct primitives is passed once.
  template <typename T, typename Emit>
  std::vector<T> collect_pairs(const Bvh& other, const Emit& emit) const;
  /// As collect_pairs, on the calling thread, appending to `sink`: for many small trees
  /// searched in parallel by the caller.
  template <typename T, typename Emit>
  void append_pairs(const Bvh& other, const Emit& emit, std::vector<T>& sink) const {
    if (!nodes_.empty() && !other.nodes_.empty()) descend_pairs(other, NodePair{0, 0}, emit, sink);
  }

 private:
  /// Depth of the stacks used while descending; median splits keep the depth near
  /// log2(n / kLeafSize), so this bounds the tree size far beyond any mesh.
  static constexpr int kMaxDepth = 128;
  /// Node pairs to split the pair search into before the parallel descent.
  static constexpr std::size_t kPairTasks = 256;

  /// A box in single precision, 4 lanes (the fourth always overlaps), for SIMD compares.
  struct FloatBox {
    Eigen::Array4f min, max;
    /// The smallest float box containing `box`; an empty box stays empty.
    static FloatBox outward(const Eigen::AlignedBox3d& box);
    bool intersects(const FloatBox& other) const {
      return ((min <= other.max) && (other.min <= max)).all();
    }
    void extend(const FloatBox& other) {
      min = min.min(other.min);
      max = max.max(other.max);
    }
    float half_perimeter() const { return (max - min).head<3>().sum(); }
  };

  /// Leaf: count > 0 primitives at [first, first + count) of ids_/boxes_. Internal:
  /// count == 0, left child at the next index, right child at `first`.
  struct Node {
    FloatBox box;
    int first;
    int count;
  };
  using NodePair = std::pair<int, int>;

  void build_node(int node, int begin, int end);
  /// The children pairs of a node pair that still need a descent (self: this == &other).
  template <typename Push>
  void split_pair(const Bvh& other, NodePair pair, const Push& push) const;
  template <typename T, typename Emit>
  void descend_pairs(const Bvh& other, NodePair start, const Emit& emit,
                     std::vector<T>& sink) const;

  std::vector<Node> nodes_;
  std::vector<int> ids_;         ///< primitive ids in leaf order
  std::vector<FloatBox> boxes_;  ///< their boxes, in leaf order
};

template <typename Push>
void Bvh::split_pair(const Bvh& other, NodePair pair, const Push& push) const {
  const auto [a, b] = pair;
  const Node& na = nodes_[static_cast<std::size_t>(a)];
  const Node& nb = other.nodes_[static_cast<std::size_t>(b)];
  if (this == &other && a == b) {
    // Within one internal node: both children, and the pairs across them.
    const int left = a + 1, right = na.first;
    push(NodePair{left, left});
    push(NodePair{right, right});
    push(NodePair{left, right});
    return;
  }
  // Descend the node that is an internal node with the larger box.
  const bool split_a =
      nb.count > 0 || (na.count == 0 && na.box.half_perimeter() >= nb.box.half_perimeter());
  if (split_a) {
    push(NodePair{a + 1, b});
    push(NodePair{na.first, b});
  } else {
    push(NodePair{a, b + 1});
    push(NodePair{a, nb.first});
  }
}

template <typename T, typename Emit>
void Bvh::descend_pairs(const Bvh& other, NodePair start, const Emit& emit,
                        std::vector<T>& sink) const {
  const bool self = this == &other;
  NodePair stack[2 * kMaxDepth + 4];
  int top = 0;
  stack[top++] = start;
  while (top > 0) {
    const NodePair pair = stack[--top];
    const Node& na = nodes_[static_cast<std::size_t>(pair.first)];
    const Node& nb = other.nodes_[static_cast<std::size_t>(pair.second)];
    const bool same = self && pair.first == pair.second;
    if (!same && !na.box.intersects(nb.box)) continue;
    if (na.count > 0 && nb.count > 0) {
      for (int i = na.first; i < na.first + na.count; ++i) {
        const FloatBox& box = boxes_[static_cast<std::size_t>(i)];
        for (int j = same ? i + 1 : nb.first; j < nb.first + nb.count; ++j)
          if (box.intersects(other.boxes_[static_cast<std::size_t>(j)]))
            emit(ids_[static_cast<std::size_t>(i)], other.ids_[static_cast<std::size_t>(j)], sink);
      }
      continue;
    }
    split_pair(other, pair, [&](NodePair child) { stack[top++] = child; });
  }
}

template <typename T, typename Emit>
std::vector<T> Bvh::collect_pairs(const Bvh& other, const Emit& emit) const {
  std::vector<T> out;
  if (nodes_.empty() || other.nodes_.empty()) return out;
  // Split the search breadth-first into independent node pairs, then descend each in
  // parallel into its own sink.
  std::vector<NodePair> tasks{{0, 0}}, next;
  const bool self = this == &other;
  while (tasks.size() < kPairTasks) {
    next.clear();
    bool split_any = false;
    for (const NodePair& pair : tasks) {
      const Node& na = nodes_[static_cast<std::size_t>(pair.first)];
      const Node& nb = other.nodes_[static_cast<std::size_t>(pair.second)];
      const bool same = self && pair.first == pair.second;
      if (!same && !na.box.intersects(nb.box)) continue;
      if ((na.count > 0 && nb.count > 0) || (same && na.count > 0)) {
        next.push_back(pair);
        continue;
      }
      split_any = true;
      split_pair(other, pair, [&](NodePair child) { next.push_back(child); });
    }
    tasks.swap(next);
    if (!split_any) break;
  }
  std::vector<std::vector<T>> sinks(tasks.size());
  tbb::parallel_for(std::size_t{0}, tasks.size(),
                    [&](std::size_t t) { descend_pairs(other, tasks[t], emit, sinks[t]); });
  std::size_t total = 0;
  for (const auto& sink : sinks) total += sink.size();
  out.reserve(total);
  for (const auto& sink : sinks) out.insert(out.end(), sink.begin(), sink.end());
  return out;
}

}  // namespace gr
