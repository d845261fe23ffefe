#pragma once

#include "core/common/types.hpp"

namespace gr {

/// A latitude–longitude sphere, closed and outward-oriented: poles on the z axis (rows 0
/// and 1), then `rings` − 1 rings of `segments` vertices; 2·segments·(rings − 1) faces.
/// @pre rings >= 2, segments >= 3, radius > 0.
TriangleMesh uv_sphere(double radius, const Vector3d& center, int rings = 24, int segments = 48);

}  // namespace gr
