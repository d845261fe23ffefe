#include "scenes/synthetic/skeleton_free_scenes.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "core/mesh/primitives.hpp"

namespace gr {

namespace {

constexpr double kPi = 3.14159265358979323846;
/// Segments around the bodies: smooth at the scenes' scale, cheap to shrink and certify.
constexpr int kBodySegments = 48;

/// Turns every face of a convex body to face away from `inside`, a point within it.
void orient_away_from(TriangleMesh& mesh, const Vector3d& inside) {
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    const Vector3d a = mesh.vertices.row(mesh.faces(f, 0)).transpose();
    const Vector3d b = mesh.vertices.row(mesh.faces(f, 1)).transpose();
    const Vector3d c = mesh.vertices.row(mesh.faces(f, 2)).transpose();
    if ((b - a).cross(c - a).dot((a + b + c) / 3.0 - inside) < 0.0)
      std::swap(mesh.faces(f, 1), mesh.faces(f, 2));
  }
}

/// Flips every face when the closed mesh's signed volume is negative.
void orient_outward(TriangleMesh& mesh) {
  double volume = 0.0;
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    volume +=
        mesh.vertices.row(mesh.faces(f, 0))
            .dot(mesh.vertices.row(mesh.faces(f, 1)).cross(mesh.vertices.row(mesh.faces(f, 2))));
  if (volume < 0.0) mesh.faces.col(1).swap(mesh.faces.col(2));
}

/// Points with their poles welded: rows 0 and `rings` of a latitude-longitude grid collapse.
TriangleMesh sphere(double radius) {
  const int rings = kBodySegments / 2;
  TriangleMesh grid = quad_grid(rings - 2, kBodySegments, true, [&](int i, int j) {
    const double theta = kPi * (i + 1) / rings, phi = 2.0 * kPi * j / kBodySegments;
    return Vector3d(radius * std::sin(theta) * std::cos(phi),
                    radius * std::sin(theta) * std::sin(phi), radius * std::cos(theta));
  });
  const auto ring_vertices = static_cast<int>(grid.vertices.rows());
  TriangleMesh mesh;
  mesh.vertices.resize(ring_vertices + 2, 3);
  mesh.vertices.topRows(ring_vertices) = grid.vertices;
  mesh.vertices.row(ring_vertices) << 0.0, 0.0, radius;
  mesh.vertices.row(ring_vertices + 1) << 0.0, 0.0, -radius;
  mesh.faces.resize(grid.faces.rows() + 2 * kBodySegments, 3);
  mesh.faces.topRows(grid.faces.rows()) = grid.faces;
  const int last_ring = ring_vertices - kBodySegments;
  for (int j = 0; j < kBodySegments; ++j) {
    const int next = (j + 1) % kBodySegments;
    mesh.faces.row(grid.faces.rows() + 2 * j) << ring_vertices, j, next;
    mesh.faces.row(grid.faces.rows() + 2 * j + 1) << ring_vertices + 1, last_ring + j,
        last_ring + next;
  }
  orient_away_from(mesh, Vector3d::Zero());
  return mesh;
}

TriangleMesh cone(double height, double radius) {
  TriangleMesh mesh;
  mesh.vertices.resize(kBodySegments + 2, 3);
  mesh.vertices.row(0) << 0.0, 0.0, height;
  mesh.vertices.row(kBodySegments + 1) << 0.0, 0.0, 0.0;
  for (int j = 0; j < kBodySegments; ++j) {
    const double phi = 2.0 * kPi * j / kBodySegments;
    mesh.vertices.row(1 + j) << radius * std::cos(phi), radius * std::sin(phi), 0.0;
  }
  mesh.faces.resize(2 * kBodySegments, 3);
  for (int j = 0; j < kBodySegments; ++j) {
    const int a = 1 + j, b = 1 + (j + 1) % kBodySegments;
    mesh.faces.row(2 * j) << 0, a, b;
    mesh.faces.row(2 * j + 1) << kBodySegments + 1, b, a;
  }
  orient_away_from(mesh, Vector3d(0.0, 0.0, height / 3.0));
  return mesh;
}

/// A ring torus about the Z axis: major radius `major`, tube radius `tube`.
TriangleMesh torus(double major, double tube) {
  TriangleMesh mesh = quad_grid(kBodySegments / 2, kBodySegments, true, [&](int i, int j) {
    const double v = 2.0 * kPi * i / (kBodySegments / 2), u = 2.0 * kPi * j / kBodySegments;
    return Vector3d((major + tube * std::cos(v)) * std::cos(u),
                    (major + tube * std::cos(v)) * std::sin(u), tube * std::sin(v));
  });
  // The last ring of tube points coincides with the first: weld it.
  const auto ring = kBodySegments;
  const auto rows = mesh.vertices.rows() / ring - 1;
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (mesh.faces(f, k) >= rows * ring) mesh.faces(f, k) -= static_cast<int>(rows * ring);
  mesh.vertices.conservativeResize(rows * ring, 3);
  orient_outward(mesh);
  return mesh;
}

/// A flat square patch `size` wide, `cells` cells across, at height z, centred at (x, 0).
TriangleMesh patch(int cells, double size, double x, double z) {
  const double step = size / cells;
  return quad_grid(cells, cells, false, [&](int i, int j) {
    return Vector3d(x - 0.5 * size + step * j, -0.5 * size + step * i, z);
  });
}

/// An open tube about the Z axis through (x, 0) from z0 to z1, `around` segments,
/// square-ish cells.
TriangleMesh sleeve(int around, double radius, double z0, double z1, double x) {
  const double cell = 2.0 * kPi * radius / around;
  const int rings = std::max(2, static_cast<int>(std::lround((z1 - z0) / cell)));
  TriangleMesh mesh = open_cylinder(radius, z0, z1, rings + 1, around);
  mesh.vertices.col(0).array() += x;
  return mesh;
}

void move(TriangleMesh& mesh, const SkeletonFreeVariant& variant) {
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(variant.turn_degrees * kPi / 180.0, Vector3d::Ones().normalized())
          .toRotationMatrix();
  mesh.vertices =
      ((variant.scale * mesh.vertices * turn.transpose()).rowwise() + variant.origin.transpose())
          .eval();
}

}  // namespace

const char* to_string(SkeletonFreeFamily family) {
  switch (family) {
    case SkeletonFreeFamily::kPatchSphere: return "patch_sphere";
    case SkeletonFreeFamily::kPatchCone: return "patch_cone";
    case SkeletonFreeFamily::kPatchTorus: return "patch_torus";
    case SkeletonFreeFamily::kSleeveBox: return "sleeve_box";
    case SkeletonFreeFamily::kSleeveSphere: return "sleeve_sphere";
  }
  return "unknown";
}

std::vector<SkeletonFreeFamily> all_skeleton_free_families() {
  return {SkeletonFreeFamily::kPatchSphere, SkeletonFreeFamily::kPatchCone,
          SkeletonFreeFamily::kPatchTorus, SkeletonFreeFamily::kSleeveBox,
          SkeletonFreeFamily::kSleeveSphere};
}

SkeletonFreeScene make_skeleton_free_scene(SkeletonFreeFamily family,
                                           const SkeletonFreeVariant& variant) {
  if (variant.resolution < 4)
    throw std::invalid_argument("skeleton-free scene: resolution must be at least 4");
  if (!(variant.scale > 0.0)) throw std::invalid_argument("skeleton-free scene: scale must be > 0");
  SkeletonFreeScene scene;
  scene.name = fmt::format("{} resolution {} offset {:g} turn {:g} scale {:g}", to_string(family),
                           variant.resolution, variant.offset, variant.turn_degrees, variant.scale);
  const int n = variant.resolution;
  const double d = variant.offset;
  // Each body pokes through its garment by a few hundredths of its size.
  switch (family) {
    case SkeletonFreeFamily::kPatchSphere:
      scene.avatar = sphere(1.0);
      scene.garment = patch(n, 1.5, d, 0.95);
      break;
    case SkeletonFreeFamily::kPatchCone:
      scene.avatar = cone(1.0, 0.6);
      scene.garment = patch(n, 1.0, d, 0.92);
      break;
    case SkeletonFreeFamily::kPatchTorus:
      scene.avatar = torus(0.7, 0.3);
      scene.garment = patch(n, 2.2, d, 0.26);
      break;
    case SkeletonFreeFamily::kSleeveBox:
      scene.avatar = box(Vector3d(0.3, 0.3, 0.8));
      scene.garment = sleeve(n, 0.41, -0.5, 0.5, d);
      break;
    case SkeletonFreeFamily::kSleeveSphere:
      scene.avatar = sphere(1.0);
      scene.garment = sleeve(n, 0.97, -0.6 + d, 0.6 + d, 0.0);
      break;
  }
  move(scene.avatar, variant);
  move(scene.garment, variant);
  return scene;
}

}  // namespace gr
