#pragma once

#include "core/ccd/ccd.hpp"
#include "core/solver/projected_newton.hpp"

namespace gr {

/// Weights, tolerances and caps of the inflation (Step 2) and fit (Step 3). Defaults are
/// the paper's (supplement 1.3); every length is in normalized scene units (body ≈ 2 tall).
struct RetargetParameters {
  double w_surf = 1.0;
  double w_contact = 1e8;
  double dhat = 0.002;  ///< barrier support (a distance)
  /// Barrier support in the fit step, where a thinner barrier lets the garment settle
  /// closer to the body; 0: dhat. The fit starts where the inflation left every pair
  /// apart, so any positive value is safe.
  double fit_dhat = 0.0;
  double fit_support() const { return fit_dhat > 0.0 ? fit_dhat : dhat; }
  double w_pos = 10.0;  ///< only used when skeletons are given
  /// Without skeletons nothing else holds the garment's size and place in the fit, which
  /// pulls every fit face near the body onto it, so two fit-step terms do: edge stretch
  /// against the input garment (StretchEnergy) and its boundary loops held at their input
  /// places (AnchorEnergy). Both are off with skeletons and in the inflation, where the
  /// garment must move wherever the avatar grows through it (held there, a cap inside a
  /// sphere stalled the push on t before t = 1).
  double w_stretch = 1.0;
  double w_anchor = 10.0;
  /// Without skeletons, in the inflation: every vertex pulled to where the round started,
  /// weighted by its share of the garment's area (AnchorEnergy "tether", a proximal term
  /// renewed every augmented-Lagrangian round). Without it the inflation's minimum puts a
  /// free-floating garment anywhere clear of the body; too weak, steps creep at the trust
  /// radius; too strong, it holds the garment against the avatar's push so that t stalls
  /// (bench/results/parameter_choices.md).
  double w_tether = 0.01;
  /// With skeletons, in the fit: edge stretch against the input garment scaled to the
  /// inflated garment's median edge ratio (StretchEnergy), so the fit keeps the pattern
  /// and leaves the size to the inflation and L_pos; stronger keeps the pattern better and
  /// fits less close (bench/results/parameter_choices.md).
  double w_fit_stretch = 0.03;
  /// The ties holding the copies of a split non-manifold edge on their originals
  /// (TieEnergy): stiff against the shape and fit terms, so that the copies stay close and
  /// welding them back in the written file moves little (the certificate checks the
  /// welded file).
  double w_tie = 1e6;
  /// Pieces laid on or through another piece held at their place on it (AttachmentEnergy):
  /// firm against the shape terms, so that a belt or a strap moves with the cloth it
  /// crosses instead of sliding through it.
  double w_attach = 1e4;
  double w_fit = 2.0;  ///< fit step only
  /// A frame of an animation, corrected: every vertex pulled toward where skinning puts it,
  /// weighted by its share of the garment's area (GarmentScene::tracked), against the
  /// shape term that keeps the garment's rest shape.
  double w_track = 100.0;
  /// The fit's Newton step cap; 0: newton.max_iterations, as every inflation round.
  int fit_max_iterations = 0;
  int fit_iteration_cap() const {
    return fit_max_iterations > 0 ? fit_max_iterations : newton.max_iterations;
  }
  /// The Newton step cap of a fit that starts where a coarse proxy's fit led (coarse to
  /// fine): it polishes a nearly converged garment; 0: fit_iteration_cap().
  int guided_fit_max_iterations = 0;
  /// The Newton step cap of a corrected animation frame's settling toward its skinned place
  /// (the fit with GarmentScene::tracked): each step stays free, and the next frame goes on
  /// from where it stopped, so fewer steps trade larger corrections for less time.
  int settle_max_iterations = 4;
  int fit_samples_per_face = 3;  ///< quadrature points per face for L_fit: 1, 3 or 6
  bool self_contact = true;      ///< model garment–garment contact
  /// Model it everywhere, also inside regions that provably cannot fold onto themselves
  /// during a step (core/candidates/fold_free_regions.hpp).
  bool self_contact_everywhere = false;

  /// eps_tol, step tolerance, iteration cap of each solve; a Newton step moves no vertex
  /// (garment, or avatar through t) more than 0.1 units at once (in the fit; the inflation
  /// has its own cap below); new contact pairs up to
  /// 0.1% of the Hessian's pattern reuse its symbolic analysis; a factorization of at least
  /// 1e9 operations (a garment of about 15k faces) is reused across steps.
  NewtonOptions newton = [] {
    NewtonOptions options;
    options.max_step_length = 0.1;
    options.pattern_slack = 0.001;
    options.reuse_factor_flops = 1e9;
    return options;
  }();
  /// The inflation's cap on a Newton step's vertex motion (instead of newton's). Small
  /// steps keep the garment following the growing avatar rather than jumping ahead of it
  /// and catching on it (bench/results/parameter_choices.md).
  double inflation_step_length = 0.025;
  CcdOptions ccd;

  // Augmented Lagrangian (Algorithm 1).
  double initial_lambda1 = 1.0;
  double max_lambda1 = 1e6;  ///< lambda1 doubles while below this and eta < eta_target
  double eta_target = 0.99;
  int max_al_rounds = 60;  ///< Newton solves before giving up
  /// Rounds in a row in which t gains less than 1% of its remaining distance to 1 before
  /// the inflation gives up as stalled: a garment pinched between growing parts of the
  /// avatar holds t for good, and further rounds only double lambda1 to its cap.
  int max_stalled_rounds = 3;
};

}  // namespace gr
