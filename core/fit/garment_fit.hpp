#pragma once

#include <map>
#include <string>
#include <vector>

#include "core/inflation/garment_problem.hpp"
#include "core/solver/guide_path.hpp"

namespace gr {

struct FitResult {
  NewtonResult solve;  ///< status, iterations, energy; check solve.converged()
  MatrixX3d garment;   ///< #Vg×3, the last accepted point whatever the status
  /// Mean fraction of garment faces whose self-contact was left out as fold free per step.
  double fold_free_fraction = 0.0;
  GuideFollowed guide;  ///< how far the guide led (no points without one)

  // Measured on the problem the fit minimized, at the returned garment.
  /// The terms it modelled (GarmentProblem::term_names).
  std::vector<std::string> terms;
  /// Each term's weighted value (GarmentProblem::term_values).
  std::map<std::string, double> energies;
  /// Smallest garment–avatar or garment–garment distance among pairs within the fit's
  /// barrier support, normalized units (+inf when none is that close).
  double min_distance = 0.0;
  /// Per boundary loop held by L_pos, its offset from its place along its bone (in bone
  /// lengths) and its vertex count; empty without skeletons.
  std::vector<double> loop_offsets;
  std::vector<int> loop_sizes;
};

/// Median over the edges of `rest` (of positive length) of deformed length / rest length;
/// 1 when no edge has a positive length.
double median_edge_ratio(const TriangleMesh& rest, const Eigen::Ref<const MatrixX3d>& deformed);

/// Step 3: t fixed at 1, one projected Newton solve on the garment vertices with L_surf
/// (rest shape: the initial garment scene.garment) + L_contact + L_pos at t = 1 (with
/// skeletons) + w_fit L_fit.
/// @param inflated #Vg×3, the inflation's result: intersection free against A.
/// @throw std::invalid_argument when scene.distance_field is null or the sample count is
///        not 1, 3 or 6; InputError as GarmentProblem's constructor.
/// @param guide points in the fit's dofs (the garment's #Vg×3 positions row by row) that the
///        garment passes through before the solve (follow_guide); when it followed them to
///        the end, the solve stops after parameters.guided_fit_max_iterations steps (when
///        positive).
/// @param interrupter sees every Newton step of the solve (ProjectedNewton::minimize).
/// @throw Interrupted from `interrupter`.
FitResult fit_garment(const GarmentScene& scene, const Eigen::Ref<const MatrixX3d>& inflated,
                      const RetargetParameters& parameters,
                      Interrupter& interrupter = null_interrupter(), const GuidePath& guide = {});

}  // namespace gr
