#include "core/mesh/primitives.hpp"

#include <cmath>
#include <vector>

namespace gr {

TriangleMesh uv_sphere(double radius, const Vector3d& center, int rings, int segments) {
  TriangleMesh mesh;
  mesh.vertices.resize(2 + (rings - 1) * segments, 3);
  mesh.vertices.row(0) = (center + Vector3d(0, 0, radius)).transpose();
  mesh.vertices.row(1) = (center - Vector3d(0, 0, radius)).transpose();
  const double pi = 3.14159265358979323846;
  for (int r = 1; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const double theta = pi * r / rings, phi = 2 * pi * s / segments;
      mesh.vertices.row(2 + (r - 1) * segments + s) =
          (center + radius * Vector3d(std::sin(theta) * std::cos(phi),
                                      std::sin(theta) * std::sin(phi), std::cos(theta)))
              .transpose();
    }
  auto ring = [&](int r, int s) { return 2 + (r - 1) * segments + (s % segments); };
  std::vector<Eigen::Vector3i> faces;
  for (int s = 0; s < segments; ++s) {
    faces.emplace_back(0, ring(1, s), ring(1, s + 1));
    faces.emplace_back(1, ring(rings - 1, s + 1), ring(rings - 1, s));
    for (int r = 1; r + 1 < rings; ++r) {
      faces.emplace_back(ring(r, s), ring(r + 1, s), ring(r + 1, s + 1));
      faces.emplace_back(ring(r, s), ring(r + 1, s + 1), ring(r, s + 1));
    }
  }
  mesh.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    mesh.faces.row(static_cast<Eigen::Index>(f)) = faces[f].transpose();
  return mesh;
}

}  // namespace gr
