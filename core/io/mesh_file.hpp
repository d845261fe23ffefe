#pragma once

#include <string>

#include "core/common/types.hpp"

namespace gr {

/// Writes `mesh` as a plain OBJ file: one `v x y z` line per vertex (#V×3, in order, in
/// the mesh's own units), then one `f a b c` line per face (#F×3, 1-based), and nothing
/// else (no header, normals, groups or materials). Numbers in full precision (`%.17g`, as
/// write_obj of an ObjDocument writes them), so read_obj gives back the same doubles. The
/// file is written to a temporary name and renamed: no partial file is ever left.
/// Degenerate faces (repeated or collinear corners) are written as they are.
/// @pre every vertex coordinate finite; every face index in [0, #V).
/// @throw std::invalid_argument when a coordinate is not finite or a face index is out of
///        range (nothing is written: a malformed file is never made).
/// @throw OutputError when the file cannot be written.
void write_obj(const std::string& path, const TriangleMesh& mesh);

}  // namespace gr
