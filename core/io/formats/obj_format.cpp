#include "core/io/formats/obj_format.hpp"

#include <filesystem>

#include <fmt/format.h>

#include "core/common/errors.hpp"

namespace gr {

namespace {

MeshFileContents read_obj_file(const std::string& path, const MeshReadOptions& /*options*/) {
  return {read_obj(path), std::nullopt};
}

std::vector<std::string> write_obj_file(const std::string& path, const std::vector<GlbMesh>& meshes,
                                        const MeshWriteOptions& options) {
  if (meshes.size() != 1 || meshes.front().document == nullptr)
    throw OutputError(fmt::format("{}: an OBJ file holds one mesh, not {}", path, meshes.size()));
  const GlbMesh& mesh = meshes.front();
  std::vector<std::string> warnings;
  if (options.copy_materials)
    warnings =
        copy_material_files(*mesh.document, std::filesystem::path(path).parent_path().string(),
                            options.allow_external_assets);
  write_obj(path, *mesh.document, mesh.positions);
  return warnings;
}

}  // namespace

const MeshFormat& obj_format() {
  static const MeshFormat format{"obj", "OBJ", {".obj"},       false,          false,
                                 false, true,  &read_obj_file, &write_obj_file};
  return format;
}

}  // namespace gr
