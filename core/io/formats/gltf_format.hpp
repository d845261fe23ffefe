#pragma once

#include "core/io/formats/mesh_format.hpp"

namespace gr {

/// glTF 2.0: reads binary `.glb` and JSON `.gltf` (read_gltf_meshes: named meshes, skins,
/// materials), writes binary `.glb` (write_glb_meshes: several skinned meshes in a file).
const MeshFormat& gltf_format();

}  // namespace gr
