#pragma once

#include <string>

#include <tiny_gltf.h>

namespace gr {

/// The tinygltf model behind a GltfDocument (see gltf_document.hpp).
struct GltfModel {
  tinygltf::Model model;
};

/// Parses a glTF file (GLB or JSON) as the readers of core/io do: buffers only from the
/// asset's folder, images kept encoded, compressed geometry refused.
/// @throw InputError naming `path` for a file that is not glTF, cannot be parsed, refers
///        outside its folder or uses a compression extension.
tinygltf::Model load_gltf_model(const std::string& path);

}  // namespace gr
