#include "core/broad_phase/refitted_tree.hpp"

#include <utility>

namespace gr {

void RefittedTree::update(std::vector<Eigen::AlignedBox3d> boxes) {
  if (tree.size() == static_cast<int>(boxes.size()) && tree.size() > 0) {
    tree.refit(boxes);
    if (tree.looseness() <= kMaxLoosening * built_looseness) return;
  }
  tree.build(std::move(boxes));
  built_looseness = tree.looseness();
}

}  // namespace gr
