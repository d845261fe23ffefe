#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "core/common/types.hpp"

namespace gr {

class TextFile;

/// One corner of an OBJ face: 0-based indices into the document's positions, texture
/// coordinates and normals; -1 where the face gives none.
struct ObjCorner {
  int position = -1;
  int texcoord = -1;
  int normal = -1;
};

/// A statement that is not geometry (`o`, `g`, `usemtl`, `s`, and any other), kept
/// verbatim and replayed in order on export so groups and materials survive.
struct ObjStatement {
  std::string text;    ///< the whole line, trimmed
  int first_face = 0;  ///< index of the first face after the statement
};

/// An OBJ file as read: everything needed to write it back with moved positions.
/// Polygons are fan-triangulated on read, so every face has three corners.
struct ObjDocument {
  std::string source_path;
  MatrixX3d positions;  ///< #P×3, every `v` line in order
  std::vector<std::string>
      position_extras;  ///< per `v`: tokens after x y z (w, colours); empty when none
  std::vector<std::array<double, 3>> texcoords;  ///< every `vt` line (u, v, w; w = 0 when absent)
  std::vector<int> texcoord_arity;               ///< how many numbers each `vt` line had
  MatrixX3d normals;                             ///< #N×3, every `vn` line in order
  std::vector<std::array<ObjCorner, 3>> faces;   ///< #F triangles
  std::vector<ObjStatement> statements;          ///< `o`, `g`, `usemtl`, `s`, ... in file order
  std::vector<std::string> material_libraries;   ///< `mtllib` file names, in order
  std::vector<std::string> warnings;             ///< e.g. "12 polygons triangulated"
};

/// Reads an OBJ file (`v`, `vt`, `vn`, `f` in all four index forms with negative
/// indices, `o`, `g`, `usemtl`, `mtllib`, `s`; `l` and `p` lines are kept as statements).
/// Polygons with more than three corners are fan-triangulated and counted in warnings.
/// @throw InputError naming file and line for a missing or empty file, a malformed or
///        non-finite number, an index that is zero or out of range, a face with fewer
///        than three corners, or a file with no vertex.
ObjDocument read_obj(const std::string& path);
/// Same, from a file already read (see TextFile).
ObjDocument read_obj(const TextFile& file);

/// Writes `document` with the given positions (#P×3, same order as document.positions)
/// in full precision (`%.17g`). Normals are recomputed from the new positions: one
/// normal per distinct (input normal, position) pair, the area-weighted average of the
/// faces that share it, so smooth and sharp shading stay as in the input. The file is
/// written to a temporary name and renamed, so no partial file is ever left.
/// @throw OutputError when the file cannot be written.
void write_obj(const std::string& path, const ObjDocument& document,
               const Eigen::Ref<const MatrixX3d>& positions);

/// Copies the document's material libraries, and the texture files they reference, from
/// beside the source OBJ into `out_dir`. A reference is copied only when it stays inside
/// the OBJ's folder: relative, without `..` out of it, a regular file (not a device or
/// FIFO), and, unless `allow_external_assets`, not a symbolic link leading out of it.
/// Other references, and missing files, stay in the output as text and are returned as
/// warnings (an asset without its textures still loads).
/// @throw OutputError when a file cannot be copied.
std::vector<std::string> copy_material_files(const ObjDocument& document,
                                             const std::string& out_dir,
                                             bool allow_external_assets = false);

/// The texture file names an MTL library's text references (`map_*`, `bump`, `disp`,
/// `decal`, `refl`, `norm`), after the statement's options (`-s 1 1 1 file.png` names
/// `file.png`); names with spaces are kept whole.
std::vector<std::string> material_texture_names(std::string_view mtl_text);

}  // namespace gr
