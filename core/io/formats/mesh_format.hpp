#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/io/gltf_document.hpp"

namespace gr {

/// A mesh file as read: its surface as an OBJ-like document (positions, texture
/// coordinates, normals, faces, groups) and, for a format that carries more, what writing
/// it back in the same format needs (glTF: the model, its materials and its skin).
struct MeshFileContents {
  ObjDocument document;
  std::optional<GltfDocument> gltf;  ///< set by the glTF reader only
};

/// Which meshes of a file to read, for a format whose files hold several named meshes.
struct MeshReadOptions {
  /// The meshes (or nodes) to read, merged in this order; empty: the format's default.
  std::vector<std::string> mesh_names;
  /// With no name, read every mesh the first skin drives (a whole avatar), not just one.
  bool whole_skin = false;
};

/// How a writer treats what lies beside the mesh file.
struct MeshWriteOptions {
  /// Copy the material files and textures the document names beside the written file.
  bool copy_materials = true;
  /// Follow symbolic links out of the source's folder when copying them.
  bool allow_external_assets = false;
};

/// One file format of meshes: its name (the `--format` value), the file extensions it
/// reads, what it can hold, and its reader and writer. Each format is one unit under
/// core/io/formats/ with one registration line in mesh_formats.cpp.
struct MeshFormat {
  std::string name;                     ///< e.g. "obj", "glb"
  std::string label;                    ///< in messages: "OBJ", "GLB"
  std::vector<std::string> extensions;  ///< lower case with the dot; the first is written
  bool named_meshes = false;            ///< a file holds several meshes chosen by name
  bool several_meshes = false;          ///< one written file may hold several meshes
  bool skinned = false;                 ///< a written mesh carries its skin
  bool material_files = false;          ///< materials live in files beside the mesh's

  /// Reads `path`.
  /// @throw InputError naming the file for a file the format cannot read.
  MeshFileContents (*read)(const std::string& path, const MeshReadOptions& options) = nullptr;
  /// Writes `meshes` (at least one; exactly one unless several_meshes) into `path`, each
  /// with its positions (#P×3 of its document, in the frame the file should hold), and
  /// returns the warnings about what was left behind (a material file not copied).
  /// @throw OutputError when the file cannot be written or holds fewer meshes than given.
  std::vector<std::string> (*write)(const std::string& path, const std::vector<GlbMesh>& meshes,
                                    const MeshWriteOptions& options) = nullptr;

  /// The extension written files take ("." and the first of extensions).
  const std::string& written_extension() const { return extensions.front(); }
};

}  // namespace gr
