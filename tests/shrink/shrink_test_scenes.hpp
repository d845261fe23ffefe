#pragma once

#include <string>

#include "core/io/rig_files.hpp"
#include "test_support.hpp"
#include "tools/pipeline/normalization.hpp"
#include "tools/pipeline/scene.hpp"

namespace gr::test {

/// A shared scene in normalized units (body about 2 tall), as the pipeline sees it.
struct NormalizedScene {
  TriangleMesh garment;
  TriangleMesh avatar;
  Skeleton source_skeleton;
  Skeleton target_skeleton;
  Eigen::MatrixXd skin_weights;  ///< #J×#V or empty
};

/// garment_dir under data/garments, avatar_dir under data/avatars (skin.txt used when there).
inline NormalizedScene load_normalized_scene(const std::string& garment_dir,
                                             const std::string& avatar_dir) {
  ScenePaths paths;
  paths.garment = shared_data("garments/" + garment_dir + "/garment.obj");
  paths.avatar = shared_data("avatars/" + avatar_dir + "/avatar.obj");
  paths.source_skeleton = shared_data("garments/" + garment_dir + "/skeleton.obj");
  paths.target_skeleton = shared_data("avatars/" + avatar_dir + "/skeleton.obj");
  if (avatar_dir == "goblin") paths.skin_weights = shared_data("avatars/goblin/skin.txt");
  const Scene scene = load_scene(paths);
  const Normalization n = normalize_scene(scene);
  NormalizedScene out;
  out.garment = {n.garment_to_scene.apply_rows(scene.garment.mesh.vertices), scene.garment.mesh.faces};
  out.avatar = {n.avatar_to_scene.apply_rows(scene.avatar.mesh.vertices), scene.avatar.mesh.faces};
  out.source_skeleton = {n.garment_to_scene.apply_rows(scene.source_skeleton->joints),
                         scene.source_skeleton->bones};
  out.target_skeleton = {n.avatar_to_scene.apply_rows(scene.target_skeleton->joints),
                         scene.target_skeleton->bones};
  out.skin_weights = scene.skin_weights;
  return out;
}

/// A UV sphere (closed, outward-oriented) of the given radius and centre.
inline TriangleMesh uv_sphere(double radius, const Vector3d& center, int rings = 24, int segments = 48) {
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
  for (std::size_t f = 0; f < faces.size(); ++f) mesh.faces.row(static_cast<Eigen::Index>(f)) = faces[f].transpose();
  return mesh;
}

}  // namespace gr::test
