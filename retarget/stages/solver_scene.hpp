#pragma once

#include <string>
#include <vector>

#include "core/inflation/garment_problem.hpp"
#include "core/inflation/retarget_parameters.hpp"
#include "core/solver/guide_path.hpp"
#include "garment/repairs/inherited_crossings.hpp"
#include "retarget/run/progress.hpp"
#include "retarget/scene/normalization.hpp"

namespace gr {

/// The solver's view of the scene, shared by the inflation and the fit: the avatar faces
/// the garment can reach, the skeletons, the no-fit list and the distance field.
struct SolverScene {
  GarmentScene scene;
  /// Garment motion the contact scope allows for (normalized units).
  double scope_margin = 0.0;
  /// Per garment face, whether it fits (not no-fit).
  std::vector<bool> fit_faces;
  int avatar_faces_modelled = 0;  ///< of the avatar's faces, those the contact models
};

struct SolverSceneInput {
  const Scene& scene;  ///< the no-fit list and the split edges' ties
  const NormalizedScene& normalized;
  const MatrixX3d& shrunk_avatar;       ///< A0 (#Va×3)
  const DistanceField& distance_field;  ///< must outlive the SolverScene
  const InheritedCrossings& inherited;
  const std::vector<int>& pierced_faces;  ///< left out of the avatar contact
};

/// The solver's scene. Vertices only pierced faces hold are not fitted: nothing keeps them
/// off the body.
SolverScene make_solver_scene(const SolverSceneInput& input, const RetargetParameters& parameters);

/// After a solve that carried the garment beyond the modelled avatar faces (it may have
/// passed through one it did not see): widens the scope to every face, so that the caller
/// solves again (rare, so the price is fine). @return whether it widened.
bool widen_scope_if_left(SolverScene& solver, const MatrixX3d& garment, double dhat,
                         const char* stage_name, Progress& progress);

/// One line on how far a garment followed a proxy's path (a progress line).
std::string describe_following(const GuideFollowed& followed);

}  // namespace gr
