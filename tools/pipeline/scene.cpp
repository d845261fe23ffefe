#include "tools/pipeline/scene.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>

#include <fmt/format.h>

#include "core/common/errors.hpp"
#include "core/io/input_file.hpp"
#include "core/skeleton/skin_matching.hpp"

namespace gr {

namespace {

/// Reads a garment (one glTF mesh) or an avatar (glTF meshes merged, by default all those
/// its skin drives).
SimulationMesh load_surface(const std::string& path, const std::vector<std::string>& mesh_names,
                            const char* role, ObjDocument& document,
                            std::optional<GltfDocument>& gltf, std::vector<std::string>& warnings) {
  const bool avatar = std::string(role) == "avatar";
  if (is_gltf_path(path)) {
    GltfAsset asset = read_gltf_meshes(path, mesh_names, avatar);
    document = std::move(asset.document);
    gltf = std::move(asset.gltf);
  } else {
    if (!mesh_names.empty())
      throw InputError(path, 0, fmt::format("--{}-mesh is for glTF files only", role));
    document = read_obj(path);
  }
  warnings.insert(warnings.end(), document.warnings.begin(), document.warnings.end());
  SimulationMesh sim = make_simulation_mesh(document);
  if (sim.mesh.faces.rows() == 0)
    throw InputError(path, 0, fmt::format("{} has no (non-degenerate) triangle", role));
  if (sim.collapsed_faces > 0)
    warnings.push_back(fmt::format("{}: {} zero-area faces (repeated vertex) are not simulated",
                                   path, sim.collapsed_faces));
  return sim;
}

/// The surface energy pairs the two faces of each edge, so the solver needs an
/// edge-manifold surface: an edge shared by more than two faces is split. Beyond its first
/// two faces (in face order), each of its faces takes copies of the edge's two vertices,
/// appended at the same positions; the copies are tied to their originals, and the document
/// still names the originals, so the written file welds them back.
/// @return the edges split; `ties` gets the (copy, original) pairs.
int split_non_manifold_edges(SimulationMesh& sim, std::vector<std::array<int, 2>>& ties) {
  auto& F = sim.mesh.faces;
  std::map<std::pair<int, int>, std::vector<int>> faces_of_edge;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      faces_of_edge[{std::min(a, b), std::max(a, b)}].push_back(static_cast<int>(f));
    }
  std::map<std::pair<int, int>, int> copy_of;  // (face, original) -> copy
  std::vector<Vector3d> copies;
  int split = 0;
  for (const auto& [edge, faces] : faces_of_edge) {
    if (faces.size() <= 2) continue;
    ++split;
    for (std::size_t i = 2; i < faces.size(); ++i)
      for (const int original : {edge.first, edge.second}) {
        const int f = faces[i];
        auto [it, added] = copy_of.emplace(std::pair{f, original}, 0);
        if (added) {
          it->second = static_cast<int>(sim.mesh.vertices.rows() + copies.size());
          copies.push_back(sim.mesh.vertices.row(original).transpose());
          sim.sim_to_obj.push_back(sim.sim_to_obj[static_cast<std::size_t>(original)]);
          ties.push_back({it->second, original});
        }
        for (int k = 0; k < 3; ++k)
          if (F(f, k) == original) F(f, k) = it->second;
      }
  }
  const Eigen::Index old_count = sim.mesh.vertices.rows();
  sim.mesh.vertices.conservativeResize(old_count + static_cast<Eigen::Index>(copies.size()), 3);
  for (std::size_t c = 0; c < copies.size(); ++c)
    sim.mesh.vertices.row(old_count + static_cast<Eigen::Index>(c)) = copies[c].transpose();
  return split;
}

/// Without skeleton files, two skinned glTF files give the skeletons and skin weights.
void skeletons_from_skins(const ScenePaths& paths, Scene& scene) {
  const bool skinned_avatar =
      scene.avatar_gltf && scene.avatar_gltf->skin && scene.avatar_gltf->skin->weights.cols() > 0;
  if (skinned_avatar && !scene.avatar_skin) scene.avatar_skin = scene.avatar_gltf->skin;
  const bool both_skins = scene.garment_gltf && scene.garment_gltf->skin && scene.avatar_gltf &&
                          scene.avatar_gltf->skin;
  if (!paths.joint_map.empty() && (!both_skins || scene.source_skeleton))
    throw InputError(paths.joint_map, 0,
                     "a joint map is for skinned glTF garment and avatar without skeleton files");
  if (scene.source_skeleton || !both_skins) return;
  const JointMap map = paths.joint_map.empty() ? JointMap{} : read_joint_map(paths.joint_map);
  const SkinBinding& target_skin = *scene.avatar_gltf->skin;
  const MatchedSkeletons matched =
      match_skin_skeletons(*scene.garment_gltf->skin, target_skin, map, paths.avatar);
  scene.source_skeleton = matched.source;
  scene.target_skeleton = matched.target;
  for (const int j : matched.target_joint)
    scene.joint_names.push_back(target_skin.joints[static_cast<std::size_t>(j)].name);
  if (!skinned_avatar) return;
  // Weights of target joints left out go to the nearest kept ancestor.
  const auto& sim_to_obj = scene.avatar.sim_to_obj;
  scene.skin_weights = Eigen::MatrixXd::Zero(matched.source.joints.rows(),
                                             static_cast<Eigen::Index>(sim_to_obj.size()));
  for (std::size_t j = 0; j < matched.kept_joint_of_target.size(); ++j)
    for (std::size_t s = 0; s < sim_to_obj.size(); ++s)
      scene.skin_weights(matched.kept_joint_of_target[j], static_cast<Eigen::Index>(s)) +=
          target_skin.weights(static_cast<Eigen::Index>(j), sim_to_obj[s]);
}

}  // namespace

std::vector<std::string> input_files(const ScenePaths& paths) {
  std::vector<std::string> files;
  for (const std::string* path :
       {&paths.garment, &paths.avatar, &paths.source_skeleton, &paths.target_skeleton,
        &paths.skin_weights, &paths.no_fit, &paths.joint_map, &paths.source_body})
    if (!path->empty()) files.push_back(*path);
  return files;
}

void check_input_files(const ScenePaths& paths, double max_input_mb) {
  const double max_bytes = max_input_mb * 1048576.0;
  const auto limit = max_input_mb > 0.0 && max_bytes < static_cast<double>(UINTMAX_MAX)
                         ? static_cast<std::uintmax_t>(max_bytes)
                         : UINTMAX_MAX;
  for (const std::string& file : input_files(paths)) require_regular_file(file, limit);
}

double require_within_limits(const Scene& scene, const RunLimits& limits) {
  const auto garment_faces = static_cast<int>(scene.garment.mesh.faces.rows());
  const auto avatar_faces = static_cast<int>(scene.avatar.mesh.faces.rows());
  const auto too_many = [&](const std::string& path, const char* role, int faces) {
    if (limits.max_faces > 0 && faces > limits.max_faces)
      throw InputError(path, 0,
                       fmt::format("the {} has {} faces, more than --max-faces {}", role, faces,
                                   limits.max_faces));
  };
  too_many(scene.garment_document.source_path, "garment", garment_faces);
  too_many(scene.avatar_document.source_path, "avatar", avatar_faces);
  const double estimate = estimated_peak_memory_mb(garment_faces, avatar_faces);
  if (limits.max_memory_mb > 0.0 && estimate > limits.max_memory_mb)
    throw InputError(
        scene.garment_document.source_path, 0,
        fmt::format("a garment of {} faces on an avatar of {} faces needs about {:.0f} MB, more "
                    "than --max-memory-mb {:g}",
                    garment_faces, avatar_faces, estimate, limits.max_memory_mb));
  return estimate;
}

Scene load_scene(const ScenePaths& paths) {
  if (paths.garment.empty()) throw InputError("", 0, "no garment file given");
  if (paths.avatar.empty()) throw InputError("", 0, "no avatar file given");
  Scene scene;
  const std::vector<std::string> garment_mesh = paths.garment_mesh.empty()
                                                    ? std::vector<std::string>{}
                                                    : std::vector<std::string>{paths.garment_mesh};
  scene.garment = load_surface(paths.garment, garment_mesh, "garment", scene.garment_document,
                               scene.garment_gltf, scene.warnings);
  scene.split_edges = split_non_manifold_edges(scene.garment, scene.garment_ties);
  if (scene.split_edges > 0)
    scene.warnings.push_back(fmt::format(
        "{}: {} edges shared by more than two faces were split for the solver ({} vertex copies, "
        "tied to their originals); the written file welds them back",
        paths.garment, scene.split_edges, scene.garment_ties.size()));
  scene.avatar = load_surface(paths.avatar, paths.avatar_meshes, "avatar", scene.avatar_document,
                              scene.avatar_gltf, scene.warnings);

  if (paths.source_skeleton.empty() != paths.target_skeleton.empty())
    throw InputError(paths.source_skeleton.empty() ? paths.target_skeleton : paths.source_skeleton,
                     0, "source and target skeletons must be given together");
  if (!paths.source_skeleton.empty()) {
    scene.source_skeleton = read_skeleton(paths.source_skeleton);
    scene.target_skeleton = read_skeleton(paths.target_skeleton);
    check_skeletons_match(*scene.source_skeleton, *scene.target_skeleton, paths.target_skeleton);
  }

  if (!paths.skin_weights.empty()) {
    if (!scene.target_skeleton)
      throw InputError(paths.skin_weights, 0, "skin weights need source and target skeletons");
    const auto joints = static_cast<int>(scene.target_skeleton->joints.rows());
    const auto vertices = static_cast<int>(scene.avatar_document.positions.rows());
    const Eigen::MatrixXd per_obj_vertex = read_skin_weights(paths.skin_weights, joints, vertices);
    const auto& sim_to_obj = scene.avatar.sim_to_obj;
    scene.skin_weights.resize(joints, static_cast<Eigen::Index>(sim_to_obj.size()));
    for (std::size_t s = 0; s < sim_to_obj.size(); ++s)
      scene.skin_weights.col(static_cast<Eigen::Index>(s)) = per_obj_vertex.col(sim_to_obj[s]);
    scene.avatar_skin = skin_of_skeleton(*scene.target_skeleton, per_obj_vertex);
  }
  skeletons_from_skins(paths, scene);

  if (!paths.no_fit.empty()) {
    const auto ids =
        read_vertex_list(paths.no_fit, static_cast<int>(scene.garment_document.positions.rows()));
    for (const int id : ids) {
      const int welded = scene.garment.obj_to_sim[static_cast<std::size_t>(id)];
      if (welded >= 0) scene.no_fit.push_back(welded);
    }
    std::sort(scene.no_fit.begin(), scene.no_fit.end());
    scene.no_fit.erase(std::unique(scene.no_fit.begin(), scene.no_fit.end()), scene.no_fit.end());
  }
  return scene;
}

std::optional<SkinBinding> avatar_skin_for_export(const Scene& scene) {
  if (scene.avatar_skin) return scene.avatar_skin;
  const MatrixX3d& positions = scene.avatar_document.positions;
  if (scene.avatar_gltf && scene.avatar_gltf->skin) {
    SkinBinding skin = *scene.avatar_gltf->skin;
    skin.weights =
        nearest_bone_weights(skeleton_of_skin(skin, scene.avatar_document.source_path), positions);
    return skin;
  }
  if (scene.target_skeleton)
    return skin_of_skeleton(*scene.target_skeleton,
                            nearest_bone_weights(*scene.target_skeleton, positions));
  return std::nullopt;
}

}  // namespace gr
