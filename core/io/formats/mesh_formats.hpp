#pragma once

#include <string>
#include <vector>

#include "core/io/formats/mesh_format.hpp"

namespace gr {

/// Every registered mesh format, in registration order (mesh_formats.cpp); the first is
/// the one files with no registered extension are read as.
const std::vector<const MeshFormat*>& mesh_formats();

/// The registered formats' names, in registration order: the `--format` choices.
std::vector<std::string> mesh_format_names();

/// The format named `name` (MeshFormat::name, exact).
/// @throw std::invalid_argument listing the names when no format has it.
const MeshFormat& mesh_format_named(const std::string& name);

/// The format whose extensions hold `path`'s extension (any case); a path with none of
/// them is read as the first registered format (an OBJ: its reader names the problem).
const MeshFormat& mesh_format_for_path(const std::string& path);

/// Reads `path` with the format of its extension (mesh_format_for_path).
/// @throw InputError as that format's reader.
MeshFileContents read_mesh_file(const std::string& path, const MeshReadOptions& options = {});

/// The surface of `path` as read_mesh_file reads it: one mesh, `mesh_name` or the format's
/// default, of a format with named meshes (the name is ignored by others).
/// @throw InputError as the reader used.
ObjDocument read_surface_document(const std::string& path, const std::string& mesh_name = "");

}  // namespace gr
