#pragma once

#include <functional>

#include "core/common/types.hpp"

namespace gr {

/// A latitude–longitude sphere, closed and outward-oriented: poles on the z axis (rows 0
/// and 1), then `rings` − 1 rings of `segments` vertices; 2·segments·(rings − 1) faces.
/// @pre rings >= 2, segments >= 3, radius > 0.
TriangleMesh uv_sphere(double radius, const Vector3d& center, int rings = 24, int segments = 48);

/// An icosphere, closed and outward-oriented: the regular icosahedron (12 vertices, 20
/// faces) with each face split into four `subdivisions` times, new vertices pushed onto
/// the sphere. Rows: the icosahedron's 12 vertices, then each level's edge midpoints in the
/// order they are made; 20·4^subdivisions faces, 10·4^subdivisions + 2 vertices.
/// @pre subdivisions >= 0, radius > 0.
TriangleMesh icosphere(int subdivisions, double radius = 1.0,
                       const Vector3d& center = Vector3d::Zero());

/// A grid of (rows + 1) × (columns + 1) points `point(i, j)` (i the row, j the column)
/// joined into quads, two triangles each: the cell (i, j) gives the faces
/// ((i, j), (i, j + 1), (i + 1, j + 1)) and ((i, j), (i + 1, j + 1), (i + 1, j)), cells in
/// row-major order, so normals point along ∂point/∂j × ∂point/∂i. With `wrap_columns` the
/// column `columns` is column 0 (a tube: `point` is not called for it). Point (i, j) is
/// vertex row i·c + j, c = columns (wrapped) or columns + 1; 2·rows·columns faces.
/// @pre rows >= 1, columns >= 1 (>= 3 when wrapped).
TriangleMesh quad_grid(int rows, int columns, bool wrap_columns,
                       const std::function<Vector3d(int, int)>& point);

/// An open cylinder of `radius` about the z axis: `rings` rings of `segments` vertices,
/// ring r at z0 + (z1 − z0)·r / (rings − 1), vertex s of ring r at angle 2π·s / segments
/// (row r·segments + s). A quad_grid wrapped around: 2·segments·(rings − 1) faces,
/// outward-oriented when z1 > z0, two boundary loops (at z0 and z1).
/// @pre rings >= 2, segments >= 3, radius > 0, z0 != z1.
TriangleMesh open_cylinder(double radius, double z0, double z1, int rings, int segments);

/// An axis-aligned box about the origin, [−half, half], closed and outward-oriented: 8
/// vertices, corner c at (±half.x, ±half.y, ±half.z) with the sign of each axis k positive
/// when bit k of c is set; 12 faces, two per side, in the order −x, +x, −y, +y, −z, +z.
/// @pre half > 0 on every axis.
TriangleMesh box(const Vector3d& half);

}  // namespace gr
