#pragma once

#include <tiny_gltf.h>

namespace gr {

/// The tinygltf model behind a GltfDocument (see gltf_document.hpp).
struct GltfModel {
  tinygltf::Model model;
};

}  // namespace gr
