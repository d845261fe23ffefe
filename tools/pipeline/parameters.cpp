#include "tools/pipeline/parameters.hpp"

#include <cmath>
#include <string>

#include "core/common/errors.hpp"

namespace gr {

double energy_tolerance_for(double eps_tol) { return 10.0 * std::sqrt(eps_tol); }

const char* to_string(Quality quality) {
  switch (quality) {
    case Quality::kFast: return "fast";
    case Quality::kBalanced: return "balanced";
    case Quality::kAccurate: return "accurate";
  }
  return "unknown";
}

Quality parse_quality(const std::string& name) {
  for (const Quality quality : {Quality::kFast, Quality::kBalanced, Quality::kAccurate})
    if (name == to_string(quality)) return quality;
  throw InputError("", 0, "unknown quality '" + name + "' (fast, balanced or accurate)");
}

PipelineParameters parameters_for_quality(Quality quality) {
  PipelineParameters p;
  RetargetParameters& s = p.solver;
  if (quality == Quality::kFast) {
    s.newton.gradient_tolerance = 1e-5;
    s.newton.step_tolerance = 1e-4;
    // A cap on time. goblin_puffer at 80: 146/80 Newton steps (inflate/fit), 11.5 s, fit
    // error 1.93e-4; at 60: 130/60, 9.8 s, 2.17e-4 (its inflation's first round ends
    // sooner, so lambda1 doubles sooner). foxgirl_skirt's fit converges in 57 either way.
    s.newton.max_iterations = 60;
    // The fit's cap, a cap on time too. goblin_puffer: 56 fit steps uncapped, 3.7 s of
    // 7.8 s; at 40 its mean fit error was 2.44e-4 against 2.17e-4 at 60 (before the
    // skeleton shrink's pullback went from 0.05 to 0.25).
    s.fit_max_iterations = 40;
    s.fit_samples_per_face = 1;
    p.voxel_size = 0.02;
  } else if (quality == Quality::kBalanced) {
    s.newton.gradient_tolerance = 1e-6;
    s.newton.step_tolerance = 1e-5;
    s.newton.max_iterations = 400;
    s.fit_samples_per_face = 3;
    p.voxel_size = 0.01;
  } else {
    s.newton.gradient_tolerance = 1e-8;
    s.newton.step_tolerance = 1e-6;
    s.newton.max_iterations = 1000;
    s.fit_samples_per_face = 6;
    s.fit_dhat = 0.5 * s.dhat;
    p.voxel_size = 0.005;
  }
  s.newton.energy_tolerance = energy_tolerance_for(s.newton.gradient_tolerance);
  s.w_contact = kPresetBarrierStiffness;
  return p;
}

void ParameterOverrides::apply_to(PipelineParameters& p) const {
  RetargetParameters& s = p.solver;
  if (dhat) s.dhat = *dhat;
  if (fit_dhat) s.fit_dhat = *fit_dhat;
  if (w_contact) s.w_contact = *w_contact;
  if (w_fit) s.w_fit = *w_fit;
  if (w_pos) s.w_pos = *w_pos;
  if (w_stretch) s.w_stretch = *w_stretch;
  if (w_anchor) s.w_anchor = *w_anchor;
  if (w_tether) s.w_tether = *w_tether;
  if (w_fit_stretch) s.w_fit_stretch = *w_fit_stretch;
  if (eps_tol) {
    s.newton.gradient_tolerance = *eps_tol;
    s.newton.energy_tolerance = energy_tolerance_for(*eps_tol);
  }
  if (voxel_size) p.voxel_size = *voxel_size;
  if (ccd_min_separation_ratio) s.ccd.min_separation_ratio = *ccd_min_separation_ratio;
  if (inflation_step_length) s.inflation_step_length = *inflation_step_length;
  if (max_newton_iterations) {
    s.newton.max_iterations = *max_newton_iterations;
    s.fit_max_iterations = 0;
  }
  if (max_fit_iterations) s.fit_max_iterations = *max_fit_iterations;
  if (skeleton_pullback) p.skeleton_pullback = *skeleton_pullback;
  if (max_al_rounds) s.max_al_rounds = *max_al_rounds;
  if (fit_samples) s.fit_samples_per_face = *fit_samples;
  if (self_contact) s.self_contact = *self_contact;
  if (self_contact_everywhere) s.self_contact_everywhere = *self_contact_everywhere;
}

}  // namespace gr
