#pragma once

#include <string>
#include <vector>

#include "core/common/types.hpp"

namespace gr {

class TextFile;

/// A skeleton as an edge mesh: joints and the bones between them.
struct Skeleton {
  MatrixX3d joints;  ///< #J×3, in the file's units and frame
  MatrixX2i bones;   ///< #B×2, 0-based joint indices
};

/// Reads a skeleton OBJ (`v` joints, `l` bones; a polyline `l a b c` is split into bones).
/// @throw InputError on a malformed file, a bone index out of range, a bone joining a
///        joint to itself, or a skeleton with no bone.
Skeleton read_skeleton(const std::string& path);
/// Same, from a file already read (see TextFile).
Skeleton read_skeleton(const TextFile& file);

/// Checks that two skeletons correspond joint by joint and bone by bone (bone direction
/// may differ).
/// @throw InputError naming `target_path` when joint counts or bone lists differ.
void check_skeletons_match(const Skeleton& source, const Skeleton& target,
                           const std::string& target_path);

/// Reads skin weights: a dense text matrix, one row per joint, one column per vertex.
/// @return #J×#V weights.
/// @throw InputError when the shape is not joints × vertices, a number is malformed or
///        non-finite, or a weight is negative.
Eigen::MatrixXd read_skin_weights(const std::string& path, int joints, int vertices);

/// Reads whitespace-separated 0-based vertex ids (a no-fit list); `#` starts a comment that
/// runs to the end of its line.
/// @throw InputError on a malformed, negative or out-of-range id (>= vertex_count).
std::vector<int> read_vertex_list(const std::string& path, int vertex_count);

}  // namespace gr
