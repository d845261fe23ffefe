#include "tools/pipeline/parameters.hpp"

#include <stdexcept>

namespace gr {

RetargetParameters parameters_for_quality(const std::string& quality) {
  RetargetParameters p;  // "balanced": the paper's weights and dhat
  if (quality == "balanced") return p;
  if (quality == "fast") {
    p.eps_tol = 1e-3;
    p.max_newton_iterations = 80;
    p.voxel_size = 0.02;
    p.fit_samples = 1;
    return p;
  }
  if (quality == "accurate") {
    p.eps_tol = 1e-7;
    p.max_newton_iterations = 500;
    p.voxel_size = 0.005;
    p.fit_samples = 6;
    return p;
  }
  throw std::invalid_argument("unknown quality '" + quality + "' (fast, balanced, accurate)");
}

void ParameterOverrides::apply_to(RetargetParameters& p) const {
  if (dhat) p.dhat = *dhat;
  if (w_contact) p.w_contact = *w_contact;
  if (w_fit) p.w_fit = *w_fit;
  if (w_pos) p.w_pos = *w_pos;
  if (eps_tol) p.eps_tol = *eps_tol;
  if (voxel_size) p.voxel_size = *voxel_size;
  if (ccd_min_separation_ratio) p.ccd_min_separation_ratio = *ccd_min_separation_ratio;
  if (max_newton_iterations) p.max_newton_iterations = *max_newton_iterations;
  if (max_al_rounds) p.max_al_rounds = *max_al_rounds;
  if (fit_samples) p.fit_samples = *fit_samples;
  if (self_contact) p.self_contact = *self_contact;
}

}  // namespace gr
