#pragma once

#include <string>

#include "core/io/rig_files.hpp"
#include "retarget/scene/normalization.hpp"
#include "retarget/scene/scene.hpp"
#include "test_support.hpp"

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
  out.garment = {n.garment_to_scene.apply_rows(scene.garment.mesh.vertices),
                 scene.garment.mesh.faces};
  out.avatar = {n.avatar_to_scene.apply_rows(scene.avatar.mesh.vertices), scene.avatar.mesh.faces};
  out.source_skeleton = {n.garment_to_scene.apply_rows(scene.source_skeleton->joints),
                         scene.source_skeleton->bones};
  out.target_skeleton = {n.avatar_to_scene.apply_rows(scene.target_skeleton->joints),
                         scene.target_skeleton->bones};
  out.skin_weights = scene.skin_weights;
  return out;
}

}  // namespace gr::test
