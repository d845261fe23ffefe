#pragma once

#include <vector>

#include <Eigen/Geometry>

namespace gr {

/// A binary bounding volume hierarchy over axis-aligned boxes, for "which boxes touch this
/// one" queries. Built top-down by median splits on the longest axis of the box centres
/// (the top levels in parallel), at most kLeafSize boxes per leaf, nodes in one flat array.
/// Rebuilding costs O(n log n); a query visits O(log n + hits) nodes on well-spread boxes.
class Bvh {
 public:
  static constexpr int kLeafSize = 4;

  /// Builds over `boxes`; primitive ids are their indices. Empty boxes never match.
  void build(std::vector<Eigen::AlignedBox3d> boxes);

  /// Number of primitives.
  int size() const { return static_cast<int>(ids_.size()); }

  /// Calls `visit(id)` once for every primitive whose (closed) box intersects `query`.
  template <typename Visit>
  void query(const Eigen::AlignedBox3d& query, Visit&& visit) const {
    if (nodes_.empty()) return;
    int stack[kMaxDepth];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[static_cast<std::size_t>(stack[--top])];
      if (!node.box.intersects(query)) continue;
      if (node.count > 0) {
        for (int i = node.first; i < node.first + node.count; ++i)
          if (boxes_[static_cast<std::size_t>(i)].intersects(query)) visit(ids_[static_cast<std::size_t>(i)]);
      } else {
        stack[top++] = node.first;
        stack[top++] = static_cast<int>(&node - nodes_.data()) + 1;
      }
    }
  }

 private:
  /// Median splits keep the depth at log2(n / kLeafSize) + 1, far below this.
  static constexpr int kMaxDepth = 128;

  /// Leaf: count > 0 primitives at [first, first + count) of ids_/boxes_. Internal:
  /// count == 0, left child at the next index, right child at `first`.
  struct Node {
    Eigen::AlignedBox3d box;
    int first;
    int count;
  };

  void build_node(int node, int begin, int end, const std::vector<Eigen::Vector3d>& centres);

  std::vector<Node> nodes_;
  std::vector<int> ids_;                    ///< primitive ids in leaf order
  std::vector<Eigen::AlignedBox3d> boxes_;  ///< their boxes, in leaf order
};

}  // namespace gr
