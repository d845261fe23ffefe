#include "core/io/formats/mesh_formats.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <stdexcept>

#include <fmt/format.h>

#include "core/io/formats/gltf_format.hpp"
#include "core/io/formats/obj_format.hpp"

namespace gr {

const std::vector<const MeshFormat*>& mesh_formats() {
  // One line per format.
  static const std::vector<const MeshFormat*> formats = {
      &obj_format(),
      &gltf_format(),
  };
  return formats;
}

std::vector<std::string> mesh_format_names() {
  std::vector<std::string> names;
  for (const MeshFormat* format : mesh_formats()) names.push_back(format->name);
  return names;
}

const MeshFormat& mesh_format_named(const std::string& name) {
  for (const MeshFormat* format : mesh_formats())
    if (format->name == name) return *format;
  throw std::invalid_argument(
      fmt::format("unknown mesh format '{}' ({})", name, fmt::join(mesh_format_names(), ", ")));
}

const MeshFormat& mesh_format_for_path(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (const MeshFormat* format : mesh_formats())
    if (std::find(format->extensions.begin(), format->extensions.end(), extension) !=
        format->extensions.end())
      return *format;
  return *mesh_formats().front();
}

MeshFileContents read_mesh_file(const std::string& path, const MeshReadOptions& options) {
  return mesh_format_for_path(path).read(path, options);
}

ObjDocument read_surface_document(const std::string& path, const std::string& mesh_name) {
  MeshReadOptions options;
  if (!mesh_name.empty()) options.mesh_names = {mesh_name};
  return read_mesh_file(path, options).document;
}

}  // namespace gr
