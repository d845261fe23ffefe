#pragma once

#include "core/io/formats/mesh_format.hpp"

namespace gr {

/// Wavefront OBJ (`.obj`): one unskinned mesh per file, written as read_obj read it (groups,
/// materials, UVs) with its material files and textures copied beside it.
const MeshFormat& obj_format();

}  // namespace gr
