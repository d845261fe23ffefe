#pragma once

#include <optional>
#include <string>

namespace gr {

/// Every numerical knob of a retarget run, in normalized scene units (body about 2 tall).
/// A quality preset sets them together; each can be overridden on its own.
struct RetargetParameters {
  double dhat = 0.002;              ///< barrier support distance
  double w_contact = 1e8;           ///< barrier stiffness
  double w_fit = 2.0;               ///< fit term weight
  double w_pos = 10.0;              ///< boundary-loop position weight (with skeletons)
  double eps_tol = 1e-5;            ///< Newton stops at |gradient| ≤ eps_tol
  int max_newton_iterations = 200;  ///< per Newton solve
  int max_al_rounds = 40;           ///< augmented-Lagrangian rounds of the inflation
  double voxel_size = 0.01;         ///< signed-distance grid spacing
  int fit_samples = 3;              ///< quadrature points per fit face
  double ccd_min_separation_ratio = 0.1;  ///< CCD keeps this fraction of each pair's gap
  bool self_contact = true;         ///< model garment–garment contact
};

/// The parameters of a preset: "fast", "balanced" or "accurate".
/// @throw std::invalid_argument for any other name.
RetargetParameters parameters_for_quality(const std::string& quality);

/// Individual overrides given on the command line; unset ones keep the preset's value.
struct ParameterOverrides {
  std::optional<double> dhat, w_contact, w_fit, w_pos, eps_tol, voxel_size,
      ccd_min_separation_ratio;
  std::optional<int> max_newton_iterations, max_al_rounds, fit_samples;
  std::optional<bool> self_contact;

  void apply_to(RetargetParameters& parameters) const;
};

}  // namespace gr
