#pragma once

#include <optional>
#include <string>

#include "core/inflation/retarget_parameters.hpp"
#include "shrink/shrunk_avatar/skeleton_shrink.hpp"

namespace gr {

/// Every numerical knob of a retarget run, in normalized scene units (body about 2 tall):
/// the solver's and the signed-distance grid's. A quality preset sets them together; each
/// can be overridden on its own (overriding eps_tol also sets the energy tolerance that
/// goes with it).
struct PipelineParameters {
  RetargetParameters solver;
  double voxel_size = 0.01;  ///< signed-distance grid spacing
  /// Skeleton shrink: the first pullback tried (SkeletonShrinkOptions::pullback).
  double skeleton_pullback = SkeletonShrinkOptions{}.pullback;
};

/// Barrier stiffness of every preset: 1e6 rather than the paper's 1e8. Measured on both
/// shared scenes, the stiffer barrier makes the fit creep (line searches cut steps as pairs
/// enter the barrier) and ends no closer: balanced took 30 s against 16 s on goblin_puffer,
/// with a mean fit error of 1.22e-4 against 1.09e-4.
constexpr double kPresetBarrierStiffness = 1e6;

/// Speed against accuracy presets.
enum class Quality { kFast, kBalanced, kAccurate };

/// "fast", "balanced" or "accurate".
const char* to_string(Quality quality);
/// The preset named `name` ("fast", "balanced" or "accurate").
/// @throw InputError for any other name.
Quality parse_quality(const std::string& name);

/// The parameters of a preset: fast, balanced (the paper's weights and dhat, with the
/// barrier stiffness above) or accurate. Every preset keeps the certificate; they differ
/// in tolerances, grid resolution, fit quadrature and, for accurate, a fit barrier half as
/// thick (fit_dhat), which lets the garment settle closer.
PipelineParameters parameters_for_quality(Quality quality);

/// The Newton solver's relative energy-decrease tolerance (over its window of steps) that
/// goes with a gradient tolerance eps_tol: 10 sqrt(eps_tol), so 10% for the fast preset's
/// 1e-4, 1% for balanced (1e-6) and 0.1% for accurate (1e-8): a tighter eps_tol asks for
/// more of the slow final progress that contact causes (see NewtonOptions).
double energy_tolerance_for(double eps_tol);

/// Individual overrides given on the command line; unset ones keep the preset's value.
struct ParameterOverrides {
  std::optional<double> dhat, fit_dhat, w_contact, w_fit, w_pos, w_stretch, w_anchor, w_tether,
      w_fit_stretch, eps_tol, voxel_size, ccd_min_separation_ratio, inflation_step_length,
      skeleton_pullback;
  /// max_newton_iterations caps the fit too unless max_fit_iterations is given.
  std::optional<int> max_newton_iterations, max_fit_iterations, max_al_rounds, fit_samples;
  std::optional<bool> self_contact, self_contact_everywhere;

  void apply_to(PipelineParameters& parameters) const;
};

}  // namespace gr
