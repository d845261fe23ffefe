#include "core/io/formats/gltf_format.hpp"

namespace gr {

namespace {

MeshFileContents read_gltf_file(const std::string& path, const MeshReadOptions& options) {
  GltfAsset asset = read_gltf_meshes(path, options.mesh_names, options.whole_skin);
  return {std::move(asset.document), std::move(asset.gltf)};
}

std::vector<std::string> write_glb_file(const std::string& path, const std::vector<GlbMesh>& meshes,
                                        const MeshWriteOptions& /*options*/) {
  write_glb_meshes(path, meshes);
  return {};
}

}  // namespace

const MeshFormat& gltf_format() {
  static const MeshFormat format{"glb", "GLB", {".glb", ".gltf"}, true,           true,
                                 true,  false, &read_gltf_file,   &write_glb_file};
  return format;
}

}  // namespace gr
