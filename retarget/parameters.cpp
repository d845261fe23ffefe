#include "retarget/parameters.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "core/common/errors.hpp"

namespace gr {

namespace {

using P = PipelineParameters;
constexpr auto kReal = ParameterType::kReal;
constexpr auto kCount = ParameterType::kCount;
constexpr auto kSwitch = ParameterType::kSwitch;

const ParameterRange kPositive{0.0, true};
const ParameterRange kNonNegative{0.0, false};
const ParameterRange kAny{-1e300, false};

std::vector<ParameterRow> make_table() {
  const double dhat = RetargetParameters{}.dhat;
  return {
      {"dhat",
       "dhat",
       kReal,
       "length",
       {},
       kPositive,
       "Barrier support distance",
       1.0,
       [](const P& p) { return p.solver.dhat; },
       [](P& p, double v) { p.solver.dhat = v; }},
      {"fit_dhat",
       "fit-dhat",
       kReal,
       "length",
       {0.0, 0.0, 0.5 * dhat},
       kPositive,
       "Barrier support distance in the fit step (0 in a preset: dhat)",
       1.0,
       [](const P& p) { return p.solver.fit_support(); },
       [](P& p, double v) { p.solver.fit_dhat = v; }},
      {"w_surf",
       "",
       kReal,
       "",
       {},
       kAny,
       "Surface-shape weight",
       1.0,
       [](const P& p) { return p.solver.w_surf; },
       [](P& p, double v) { p.solver.w_surf = v; }},
      {"w_contact",
       "w-contact",
       kReal,
       "",
       {1e6, 1e6, 1e6},
       kPositive,
       "Barrier stiffness",
       1.0,
       [](const P& p) { return p.solver.w_contact; },
       [](P& p, double v) { p.solver.w_contact = v; }},
      {"w_fit",
       "w-fit",
       kReal,
       "",
       {},
       kNonNegative,
       "Fit term weight",
       1.0,
       [](const P& p) { return p.solver.w_fit; },
       [](P& p, double v) { p.solver.w_fit = v; }},
      {"w_pos",
       "w-pos",
       kReal,
       "",
       {},
       kNonNegative,
       "Boundary-loop position weight (with skeletons)",
       1.0,
       [](const P& p) { return p.solver.w_pos; },
       [](P& p, double v) { p.solver.w_pos = v; }},
      {"w_stretch",
       "w-stretch",
       kReal,
       "",
       {},
       kNonNegative,
       "Edge-stretch weight against the input garment, without skeletons only (0 switches "
       "it off)",
       1.0,
       [](const P& p) { return p.solver.w_stretch; },
       [](P& p, double v) { p.solver.w_stretch = v; }},
      {"w_anchor",
       "w-anchor",
       kReal,
       "",
       {},
       kNonNegative,
       "Weight holding boundary loops at their input places, without skeletons only (0 "
       "switches it off)",
       1.0,
       [](const P& p) { return p.solver.w_anchor; },
       [](P& p, double v) { p.solver.w_anchor = v; }},
      {"w_tether",
       "w-tether",
       kReal,
       "",
       {},
       kNonNegative,
       "Weight pulling every garment vertex to its input place (per unit area) during the "
       "inflation, without skeletons only (0 switches it off)",
       1.0,
       [](const P& p) { return p.solver.w_tether; },
       [](P& p, double v) { p.solver.w_tether = v; }},
      {"w_fit_stretch",
       "w-fit-stretch",
       kReal,
       "",
       {},
       kNonNegative,
       "Edge-stretch weight in the fit against the input garment at its inflated size, with "
       "skeletons only (0 switches it off)",
       1.0,
       [](const P& p) { return p.solver.w_fit_stretch; },
       [](P& p, double v) { p.solver.w_fit_stretch = v; }},
      {"eps_tol",
       "eps-tol",
       kReal,
       "",
       {1e-5, 1e-6, 1e-8},
       kPositive,
       "Newton stops when the gradient norm is below this (also sets the energy tolerance "
       "that goes with it)",
       1.0,
       [](const P& p) { return p.solver.newton.gradient_tolerance; },
       [](P& p, double v) {
         p.solver.newton.gradient_tolerance = v;
         p.solver.newton.energy_tolerance = energy_tolerance_for(v);
       }},
      {"step_tolerance",
       "",
       kReal,
       "length",
       {1e-4, 1e-5, 1e-6},
       kPositive,
       "Newton stops when a step moves nothing further than this",
       1.0,
       [](const P& p) { return p.solver.newton.step_tolerance; },
       [](P& p, double v) { p.solver.newton.step_tolerance = v; }},
      {"energy_tolerance",
       "",
       kReal,
       "",
       {},
       kNonNegative,
       "Newton stops when the energy decreased less than this fraction over its window",
       1.0,
       [](const P& p) { return p.solver.newton.energy_tolerance; },
       [](P& p, double v) { p.solver.newton.energy_tolerance = v; }},
      {"energy_window",
       "",
       kCount,
       "",
       {},
       kNonNegative,
       "Accepted Newton steps the energy tolerance looks back over (0: off)",
       1.0,
       [](const P& p) { return double(p.solver.newton.energy_window); },
       [](P& p, double v) { p.solver.newton.energy_window = int(v); }},
      {"max_newton_iterations",
       "max-newton-iterations",
       kCount,
       "",
       {60, 400, 1000},
       kPositive,
       "Iteration cap per Newton solve (each inflation round, and the fit unless "
       "--max-fit-iterations is given)",
       1.0,
       [](const P& p) { return double(p.solver.newton.max_iterations); },
       [](P& p, double v) {
         p.solver.newton.max_iterations = int(v);
         p.solver.fit_max_iterations = 0;
       }},
      {"max_fit_iterations",
       "max-fit-iterations",
       kCount,
       "",
       {40, 0, 0},
       kPositive,
       "Iteration cap of the fit's Newton solve (0 in a preset: as each inflation round)",
       1.0,
       [](const P& p) { return double(p.solver.fit_iteration_cap()); },
       [](P& p, double v) { p.solver.fit_max_iterations = int(v); }},
      {"skeleton_pullback",
       "pullback",
       kReal,
       "",
       {},
       ParameterRange{1e-6, false, 1.0},
       "Skeleton shrink: fraction of each avatar vertex's offset from its bone kept in the "
       "shrunk avatar (halved while it meets the garment, and a fifth of it is tried when the "
       "inflation stalls)",
       1.0,
       [](const P& p) { return p.skeleton_pullback; },
       [](P& p, double v) { p.skeleton_pullback = v; }},
      {"max_al_rounds",
       "max-al-rounds",
       kCount,
       "",
       {},
       kPositive,
       "Cap on augmented-Lagrangian rounds",
       1.0,
       [](const P& p) { return double(p.solver.max_al_rounds); },
       [](P& p, double v) { p.solver.max_al_rounds = int(v); }},
      {"voxel_size",
       "voxel-size",
       kReal,
       "length",
       {0.02, 0.01, 0.005},
       kPositive,
       "Signed-distance grid spacing",
       1.0,
       [](const P& p) { return p.voxel_size; },
       [](P& p, double v) { p.voxel_size = v; }},
      {"fit_samples_per_face",
       "fit-samples",
       kCount,
       "",
       {1, 3, 6},
       ParameterRange{1.0, false, 6.0, {1.0, 3.0, 6.0}},
       "Fit quadrature points per face",
       1.0,
       [](const P& p) { return double(p.solver.fit_samples_per_face); },
       [](P& p, double v) { p.solver.fit_samples_per_face = int(v); }},
      {"reuse_factor_gflops",
       "reuse-factor-gflops",
       kReal,
       "",
       {},
       kNonNegative,
       "Reuse a Cholesky factor across Newton steps, as the preconditioner of conjugate "
       "gradients, when one factorization costs at least this many billion operations "
       "(dense garments; 0 switches it off)",
       1.0,
       [](const P& p) { return p.solver.newton.reuse_factor_flops * 1e-9; },
       [](P& p, double v) { p.solver.newton.reuse_factor_flops = v * 1e9; }},
      {"reuse_tolerance",
       "reuse-tolerance",
       kReal,
       "",
       {1e-2, 1e-3, 1e-4},
       kPositive,
       "Relative residual of a Newton direction solved on a reused factor",
       1.0,
       [](const P& p) { return p.solver.newton.reuse_tolerance; },
       [](P& p, double v) { p.solver.newton.reuse_tolerance = v; }},
      {"proxy_faces",
       "proxy-faces",
       kCount,
       "",
       {4000, 5000, 12000},
       kNonNegative,
       "Solve a garment of more than twice this many faces on a proxy decimated to this "
       "many first, then let the garment follow its path (coarse to fine; 0 switches it "
       "off)",
       1.0,
       [](const P& p) { return double(p.proxy_faces); },
       [](P& p, double v) { p.proxy_faces = int(v); }},
      {"settle_max_iterations",
       "settle-iterations",
       kCount,
       "",
       {2, 4, 8},
       kPositive,
       "Newton step cap of an animation frame's settling toward its skinned place after a "
       "correction (--animation)",
       1.0,
       [](const P& p) { return double(p.solver.settle_max_iterations); },
       [](P& p, double v) { p.solver.settle_max_iterations = int(v); }},
      {"guided_fit_max_iterations",
       "guided-fit-iterations",
       kCount,
       "",
       {8, 15, 60},
       kNonNegative,
       "Newton step cap of a fit that follows a proxy's fit (0: the fit's own cap)",
       1.0,
       [](const P& p) { return double(p.solver.guided_fit_max_iterations); },
       [](P& p, double v) { p.solver.guided_fit_max_iterations = int(v); }},
      {"ccd_min_separation_ratio",
       "ccd-separation",
       kReal,
       "",
       {},
       ParameterRange{1e-6, false, 0.99},
       "Fraction of each pair's gap that a CCD-bounded step keeps",
       1.0,
       [](const P& p) { return p.solver.ccd.min_separation_ratio; },
       [](P& p, double v) { p.solver.ccd.min_separation_ratio = v; }},
      {"ccd_min_separation",
       "",
       kReal,
       "length",
       {},
       kNonNegative,
       "Separation every CCD-bounded step keeps",
       1.0,
       [](const P& p) { return p.solver.ccd.min_separation; },
       [](P& p, double v) { p.solver.ccd.min_separation = v; }},
      {"self_contact",
       "no-self-contact",
       kSwitch,
       "",
       {},
       ParameterRange{0.0, false, 1.0},
       "Do not model garment self-contact (the certificate still checks it)",
       0.0,
       [](const P& p) { return p.solver.self_contact ? 1.0 : 0.0; },
       [](P& p, double v) { p.solver.self_contact = v != 0.0; }},
      {"self_contact_everywhere",
       "self-contact-everywhere",
       kSwitch,
       "",
       {},
       ParameterRange{0.0, false, 1.0},
       "Model garment self-contact also inside regions that provably cannot fold onto "
       "themselves during a step (slower; the same guarantee)",
       1.0,
       [](const P& p) { return p.solver.self_contact_everywhere ? 1.0 : 0.0; },
       [](P& p, double v) { p.solver.self_contact_everywhere = v != 0.0; }},
      {"inflation_step_length",
       "inflation-step",
       kReal,
       "length",
       {},
       kPositive,
       "Largest vertex motion of one inflation step",
       1.0,
       [](const P& p) { return p.solver.inflation_step_length; },
       [](P& p, double v) { p.solver.inflation_step_length = v; }},
  };
}

std::string range_text(const ParameterRange& r) {
  if (!r.choices.empty()) {
    std::string text;
    for (std::size_t i = 0; i < r.choices.size(); ++i)
      text += (i == 0                      ? ""
               : i + 1 == r.choices.size() ? " or "
                                           : ", ") +
              fmt::format("{}", r.choices[i]);
    return text;
  }
  if (r.max >= 1e300)
    return r.min_exclusive ? fmt::format("above {}", r.min) : fmt::format("at least {}", r.min);
  return fmt::format("in [{}, {}]", r.min, r.max);
}

}  // namespace

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

const std::vector<ParameterRow>& parameter_table() {
  static const std::vector<ParameterRow> table = make_table();
  return table;
}

const ParameterRow* find_parameter(const std::string& name) {
  for (const ParameterRow& row : parameter_table())
    if (name == row.name) return &row;
  return nullptr;
}

const ParameterRow* find_parameter_option(const std::string& option) {
  std::string dashed = option;
  for (char& c : dashed)
    if (c == '_') c = '-';
  for (const ParameterRow& row : parameter_table())
    if (*row.option != '\0' && dashed == row.option) return &row;
  return nullptr;
}

std::string parameter_value_error(const ParameterRow& row, double value) {
  const ParameterRange& r = row.range;
  if (!std::isfinite(value)) return "must be a finite number";
  if (row.type != ParameterType::kReal && value != std::floor(value))
    return "must be a whole number";
  bool valid = (r.min_exclusive ? value > r.min : value >= r.min) && value <= r.max;
  if (!r.choices.empty()) {
    valid = false;
    for (double choice : r.choices) valid = valid || value == choice;
  }
  return valid ? std::string() : "must be " + range_text(r);
}

PipelineParameters parameters_for_quality(Quality quality) {
  PipelineParameters p;
  for (const ParameterRow& row : parameter_table())
    if (const std::optional<double>& value = row.preset[static_cast<int>(quality)])
      row.set(p, *value);
  return p;
}

void ParameterOverrides::set(const std::string& name, double value) {
  const ParameterRow* row = find_parameter(name);
  if (!row) throw std::invalid_argument("unknown parameter '" + name + "'");
  if (*row->option == '\0') throw std::invalid_argument("'" + name + "' is set by the preset only");
  const std::string error = parameter_value_error(*row, value);
  if (!error.empty()) throw std::invalid_argument(fmt::format("{} {}", name, error));
  values_[name] = value;
}

std::optional<double> ParameterOverrides::get(const std::string& name) const {
  const auto it = values_.find(name);
  if (it == values_.end()) return std::nullopt;
  return it->second;
}

void ParameterOverrides::apply_to(PipelineParameters& parameters) const {
  for (const ParameterRow& row : parameter_table())
    if (const auto it = values_.find(row.name); it != values_.end())
      row.set(parameters, it->second);
}

}  // namespace gr
