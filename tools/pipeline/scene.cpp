#include "tools/pipeline/scene.hpp"

#include <algorithm>
#include <map>

#include <fmt/format.h>

#include "core/common/errors.hpp"

namespace gr {

namespace {

SimulationMesh load_surface(const std::string& path, const char* role, ObjDocument& document,
                            std::vector<std::string>& warnings) {
  document = read_obj(path);
  warnings.insert(warnings.end(), document.warnings.begin(), document.warnings.end());
  SimulationMesh sim = make_simulation_mesh(document);
  if (sim.mesh.faces.rows() == 0)
    throw InputError(path, 0, fmt::format("{} has no (non-degenerate) triangle", role));
  if (sim.collapsed_faces > 0)
    warnings.push_back(fmt::format("{}: {} zero-area faces (repeated vertex) are not simulated",
                                   path, sim.collapsed_faces));
  return sim;
}

/// The surface energy pairs the two faces of each edge: an edge with three or more faces
/// has no such pair, so the garment must be an edge-manifold surface.
void require_edge_manifold(const SimulationMesh& sim, const std::string& path) {
  std::map<std::pair<int, int>, int> incidence;
  const auto& F = sim.mesh.faces;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k);
      const int b = F(f, (k + 1) % 3);
      if (++incidence[{std::min(a, b), std::max(a, b)}] == 3)
        throw InputError(path, 0,
                         fmt::format("garment edge between vertices {} and {} is shared by more "
                                     "than two faces (non-manifold)",
                                     sim.sim_to_obj[static_cast<std::size_t>(std::min(a, b))] + 1,
                                     sim.sim_to_obj[static_cast<std::size_t>(std::max(a, b))] + 1));
    }
}

}  // namespace

Scene load_scene(const ScenePaths& paths) {
  if (paths.garment.empty()) throw InputError("", 0, "no garment file given");
  if (paths.avatar.empty()) throw InputError("", 0, "no avatar file given");
  Scene scene;
  scene.garment = load_surface(paths.garment, "garment", scene.garment_document, scene.warnings);
  require_edge_manifold(scene.garment, paths.garment);
  scene.avatar = load_surface(paths.avatar, "avatar", scene.avatar_document, scene.warnings);

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
  }

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

}  // namespace gr
