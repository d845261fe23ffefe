#include "retarget/stages/solver_scene.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "core/candidates/contact_scope.hpp"
#include "core/energies/fit_energy.hpp"
#include "retarget/scene/shrink_avatar.hpp"

namespace gr {

SolverScene make_solver_scene(const SolverSceneInput& input, const RetargetParameters& parameters) {
  const NormalizedScene& normalized = input.normalized;
  SolverScene solver;
  GarmentScene& scene = solver.scene;
  scene.garment = normalized.garment;
  scene.avatar = normalized.avatar;
  scene.shrunk_avatar = input.shrunk_avatar;
  const double largest_avatar_motion =
      (normalized.avatar.vertices - input.shrunk_avatar).rowwise().norm().maxCoeff();
  solver.scope_margin = largest_avatar_motion + kDistanceBand + parameters.dhat;
  scene.avatar_faces_used = reachable_avatar_faces(normalized.garment.vertices, input.shrunk_avatar,
                                                   normalized.avatar.vertices,
                                                   normalized.avatar.faces, solver.scope_margin);
  solver.avatar_faces_modelled = static_cast<int>(scene.avatar_faces_used.size());
  // Every face in reach is every face: nothing a solve could leave, so no second solve.
  if (solver.avatar_faces_modelled == static_cast<int>(normalized.avatar.faces.rows()))
    scene.avatar_faces_used.clear();
  if (normalized.source_skeleton)
    scene.skeletons =
        SkeletonMotion{normalized.source_skeleton->joints, normalized.target_skeleton->joints,
                       normalized.target_skeleton->bones, skirt_vertices(input.scene)};
  scene.no_fit = input.scene.no_fit;
  scene.distance_field = &input.distance_field;
  scene.garment_tangles = input.inherited.tangles;
  for (const FacePair& p : input.inherited.pairs)
    scene.garment_crossing_faces.push_back(
        {std::min(p.first, p.second), std::max(p.first, p.second)});
  const std::vector<int>& pierced = input.pierced_faces;
  scene.faces_without_avatar_contact = pierced;
  if (!pierced.empty()) {
    std::vector<char> kept(static_cast<std::size_t>(normalized.garment.vertices.rows()), 0);
    for (Eigen::Index f = 0; f < normalized.garment.faces.rows(); ++f)
      if (!std::binary_search(pierced.begin(), pierced.end(), static_cast<int>(f)))
        for (int k = 0; k < 3; ++k)
          kept[static_cast<std::size_t>(normalized.garment.faces(f, k))] = 1;
    for (std::size_t v = 0; v < kept.size(); ++v)
      if (!kept[v]) scene.no_fit.push_back(static_cast<int>(v));
    std::sort(scene.no_fit.begin(), scene.no_fit.end());
    scene.no_fit.erase(std::unique(scene.no_fit.begin(), scene.no_fit.end()), scene.no_fit.end());
  }
  scene.ties = input.scene.garment_ties;
  scene.attachments = input.inherited.attachments;
  solver.fit_faces = fit_face_mask(
      normalized.garment.faces, static_cast<int>(normalized.garment.vertices.rows()), scene.no_fit);
  return solver;
}

bool widen_scope_if_left(SolverScene& solver, const MatrixX3d& garment, double dhat,
                         const char* stage_name, Progress& progress) {
  GarmentScene& scene = solver.scene;
  if (scene.avatar_faces_used.empty() ||
      within_contact_scope(scene.garment.vertices, garment, solver.scope_margin, dhat))
    return false;
  scene.avatar_faces_used.clear();
  solver.avatar_faces_modelled = static_cast<int>(scene.avatar.faces.rows());
  progress.log(stage_name, "the {} carried the garment beyond the modelled avatar faces",
               stage_name);
  progress.record_warning(fmt::format(
      "the {} carried the garment beyond the modelled avatar faces; solved again with all {}",
      stage_name, solver.avatar_faces_modelled));
  return true;
}

std::string describe_following(const GuideFollowed& followed) {
  std::string recoveries;
  if (followed.recoveries > 0)
    recoveries = fmt::format(", {} recovered from in {} Newton steps", followed.recoveries,
                             followed.recovery_steps);
  return fmt::format(
      "followed the proxy's {} points {}: {} reached exactly, {} motions held back in part, {} "
      "cut by CCD{}",
      followed.points, followed.reached_end ? "to the end" : "and left them early",
      followed.points_reached, followed.held_motions, followed.cut_motions, recoveries);
}

}  // namespace gr
