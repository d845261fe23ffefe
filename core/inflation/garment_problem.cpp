#include "core/inflation/garment_problem.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <stdexcept>

#include "core/candidates/candidates.hpp"
#include "core/mesh/boundary_loops.hpp"
#include "core/mesh/graded_values.hpp"
#include "core/solver/sparse_pattern.hpp"

namespace gr {
namespace {

DofLayout layout_for(const GarmentScene& scene, GarmentProblem::Stage stage) {
  DofLayout layout;
  layout.garment_vertex_count = static_cast<int>(scene.garment.vertices.rows());
  layout.t_free = stage == GarmentProblem::Stage::kInflation;
  layout.fixed_t = 1.0;
  return layout;
}

const GarmentScene& checked(const GarmentScene& scene, GarmentProblem::Stage stage) {
  if (scene.shrunk_avatar.rows() != scene.avatar.vertices.rows())
    throw std::invalid_argument("the shrunk avatar must have the target avatar's vertex count");
  if (scene.tracked.size() > 0 && scene.tracked.rows() != scene.garment.vertices.rows())
    throw std::invalid_argument("the tracked positions must have the garment's vertex count");
  if (stage == GarmentProblem::Stage::kFit && !scene.distance_field && scene.tracked.size() == 0)
    throw std::invalid_argument("the fit step needs the avatar's distance field");
  return scene;
}

/// Self pairs of crossing faces closer than this fraction of dhat at the start are not
/// modelled: their barrier would be unbounded or all but. Any pair further apart is.
constexpr double kTouchingGap = 1e-3;

/// hold_back: rounds of per-vertex CCD, and the share of a vertex's CCD bound it keeps in
/// each (less than all of it, since the fade moves its neighbours differently).
constexpr int kHoldBackRounds = 6;
constexpr double kHeldFraction = 0.5;

ContactMesh contact_mesh_for(const GarmentScene& scene, const RetargetParameters& parameters) {
  ContactMesh mesh = ContactMesh::build(scene.garment, scene.avatar, parameters.self_contact,
                                        scene.avatar_faces_used);
  mesh.cull_fold_free = !parameters.self_contact_everywhere;
  mesh.garment_tangles = scene.garment_tangles;
  mesh.garment_crossing_faces = scene.garment_crossing_faces;
  std::sort(mesh.garment_crossing_faces.begin(), mesh.garment_crossing_faces.end());
  mesh.unmodelled_self_pairs = crossing_pairs_closer_than(
      mesh, scene.garment.vertices, kTouchingGap * parameters.dhat, scene.ties);
  mesh.leave_out_of_avatar_contact(scene.faces_without_avatar_contact);
  return mesh;
}

}  // namespace

GarmentProblem::GarmentProblem(const GarmentScene& scene, const RetargetParameters& parameters,
                               Stage stage, double rest_scale)
    : stage_(stage), parameters_(parameters), layout_(layout_for(checked(scene, stage), stage)) {
  add_term<SurfaceShapeEnergy>(parameters.w_surf, scene.garment, layout_);
  contact_ = &add_term<ContactEnergy>(parameters.w_contact, contact_mesh_for(scene, parameters),
                                      scene.garment.vertices, scene.shrunk_avatar,
                                      scene.avatar.vertices, parameters.dhat, layout_);
  if (scene.skeletons) {
    const SkeletonMotion& s = *scene.skeletons;
    loop_bones_ = assign_loop_bones(scene.garment.vertices, boundary_loops(scene.garment.faces),
                                    s.source_joints, s.target_joints, s.bones, s.skirt_vertices);
    position_ =
        &add_term<PositionEnergy>(parameters.w_pos, scene.garment.vertices, loop_bones_, layout_);
    if (stage == Stage::kFit && parameters.w_fit_stretch > 0.0)
      add_term<StretchEnergy>(
          parameters.w_fit_stretch,
          TriangleMesh{rest_scale * scene.garment.vertices, scene.garment.faces}, layout_);
  } else if (stage == Stage::kInflation) {
    if (parameters.w_tether > 0.0) {
      std::vector<int> all(static_cast<std::size_t>(scene.garment.vertices.rows()));
      std::iota(all.begin(), all.end(), 0);
      tether_ = &add_term<AnchorEnergy>(
          parameters.w_tether, scene.garment.vertices, std::move(all), layout_,
          vertex_area_shares(scene.garment.vertices, scene.garment.faces), "tether");
    }
  } else {
    if (parameters.w_stretch > 0.0)
      add_term<StretchEnergy>(parameters.w_stretch, scene.garment, layout_);
    // A tracked frame has its own places for every vertex, boundary loops included.
    if (parameters.w_anchor > 0.0 && scene.tracked.size() == 0)
      add_term<AnchorEnergy>(parameters.w_anchor, scene.garment.vertices,
                             boundary_loop_vertices(scene.garment.faces), layout_);
  }
  if (!scene.ties.empty()) add_term<TieEnergy>(parameters.w_tie, scene.ties, layout_);
  if (!scene.attachments.empty())
    add_term<AttachmentEnergy>(parameters.w_attach, scene.attachments, layout_);
  if (stage == Stage::kFit && scene.tracked.size() > 0) {
    std::vector<int> all(static_cast<std::size_t>(scene.garment.vertices.rows()));
    std::iota(all.begin(), all.end(), 0);
    add_term<AnchorEnergy>(parameters.w_track, scene.tracked, std::move(all), layout_,
                           vertex_area_shares(scene.garment.vertices, scene.garment.faces),
                           "track");
  } else if (stage == Stage::kFit)
    add_term<FitEnergy>(parameters.w_fit, scene.garment, scene.no_fit, *scene.distance_field,
                        parameters.fit_samples_per_face, layout_, scene.fit_offsets);
  constraint_.displacement_sq = (scene.avatar.vertices - scene.shrunk_avatar).squaredNorm();
  constraint_.lambda1 = parameters.initial_lambda1;
  if (layout_.t_free) add_term<AvatarConstraintTerm>(1.0, constraint_, layout_);
}

std::vector<std::string> GarmentProblem::term_names() const {
  std::vector<std::string> names;
  for (const WeightedTerm& weighted : terms_) names.emplace_back(weighted.term->name());
  return names;
}

void GarmentProblem::tether_to(const Eigen::VectorXd& x) {
  if (tether_) tether_->set_rest(layout_.garment(x));
}

std::vector<double> GarmentProblem::loop_offsets(const Eigen::VectorXd& x) const {
  std::vector<double> offsets;
  if (!position_) return offsets;
  const auto V = layout_.garment(x);
  const double t = layout_.t(x);
  std::map<int, const PositionEnergy::Element*> element_of;
  for (const PositionEnergy::Element& element : position_->elements())
    element_of[element.vertex] = &element;
  for (const LoopBone& loop : loop_bones_) {
    double sum = 0.0;
    int count = 0;
    for (int v : loop.vertices) {
      const auto it = element_of.find(v);
      if (it == element_of.end()) continue;  // a bone of zero length holds nothing
      const PositionEnergy::Element& element = *it->second;
      // (s - s_rest)^2
      sum += 2.0 * PositionEnergy::element_value(element, PositionEnergy::gather(element, V, t));
      ++count;
    }
    offsets.push_back(count > 0 ? std::sqrt(sum / count) : 0.0);
  }
  return offsets;
}

double GarmentProblem::value(const Eigen::VectorXd& x) {
  const auto V = layout_.garment(x);
  const double t = layout_.t(x);
  double total = 0.0;
  for (const WeightedTerm& weighted : terms_) total += weighted.weight * weighted.term->value(V, t);
  return total;
}

std::map<std::string, double> GarmentProblem::term_values(const Eigen::VectorXd& x) {
  const auto V = layout_.garment(x);
  const double t = layout_.t(x);
  std::map<std::string, double> values;
  for (const WeightedTerm& weighted : terms_)
    values[weighted.term->name()] = weighted.weight * weighted.term->value(V, t);
  return values;
}

void GarmentProblem::gradient(const Eigen::VectorXd& x, Eigen::VectorXd& gradient) {
  const auto V = layout_.garment(x);
  const double t = layout_.t(x);
  for (std::size_t i = 0; i < terms_.size(); ++i) {
    const WeightedTerm& weighted = terms_[i];
    if (i == 0) {
      weighted.term->gradient(V, t, gradient);
      gradient *= weighted.weight;
      continue;
    }
    weighted.term->gradient(V, t, term_gradient_);
    gradient += weighted.weight * term_gradient_;
  }
}

void GarmentProblem::hessian_of(const Eigen::VectorXd& x, Eigen::SparseMatrix<double>& hessian,
                                bool project_psd) {
  const auto V = layout_.garment(x);
  const double t = layout_.t(x);
  // The terms whose pattern is fixed are summed into a union pattern made once. With t
  // free its whole row and column are in it too: any garment vertex may come into contact
  // with the moving avatar, and the linear solver should not have to drop those couplings.
  std::vector<const Eigen::SparseMatrix<double>*> fixed_parts;
  for (const WeightedTerm& weighted : terms_)
    if (weighted.term->fixed_pattern())
      fixed_parts.push_back(&weighted.term->hessian(V, t, project_psd));
  if (fixed_hessian_.size() == 0) {
    Eigen::SparseMatrix<double> pattern(layout_.dof_count(), layout_.dof_count());
    for (const Eigen::SparseMatrix<double>* part : fixed_parts) pattern += *part;
    if (layout_.t_free) {
      std::vector<Eigen::Triplet<double>> t_entries;
      const int t_index = layout_.t_index();
      for (int dof = 0; dof < layout_.dof_count(); ++dof) {
        t_entries.emplace_back(t_index, dof, 0.0);
        t_entries.emplace_back(dof, t_index, 0.0);
      }
      Eigen::SparseMatrix<double> t_pattern(layout_.dof_count(), layout_.dof_count());
      t_pattern.setFromTriplets(t_entries.begin(), t_entries.end());
      pattern += t_pattern;
    }
    pattern.makeCompressed();
    fixed_hessian_ = std::move(pattern);
  }
  std::fill(fixed_hessian_.valuePtr(), fixed_hessian_.valuePtr() + fixed_hessian_.nonZeros(), 0.0);
  std::size_t part = 0;
  for (const WeightedTerm& weighted : terms_)
    if (weighted.term->fixed_pattern())
      add_within_pattern(*fixed_parts[part++], weighted.weight, fixed_hessian_);
  hessian = fixed_hessian_;
  for (const WeightedTerm& weighted : terms_)
    if (!weighted.term->fixed_pattern())
      hessian = hessian + weighted.weight * weighted.term->hessian(V, t, project_psd);
  hessian.makeCompressed();
}

void GarmentProblem::solution_changed(const Eigen::VectorXd& x) {
  contact_->update_candidates(layout_.garment(x), layout_.t(x));
}

double GarmentProblem::max_step(const Eigen::VectorXd& x, const Eigen::VectorXd& dx) {
  const Eigen::VectorXd end = x + dx;
  return contact_->update_swept_candidates(layout_.garment(x), layout_.t(x), layout_.garment(end),
                                           layout_.t(end), parameters_.ccd);
}

void GarmentProblem::hold_back(const Eigen::VectorXd& x, Eigen::VectorXd& dx, double fade_length) {
  const auto start = layout_.garment(x);
  const MatrixX3d motion = layout_.garment(dx);
  const double dt = layout_.t_free ? dx[layout_.t_index()] : 0.0;
  const double t0 = layout_.t(x);
  const double t1 = t0 + dt;
  MatrixX3d held = motion;
  std::vector<double> scale(static_cast<std::size_t>(motion.rows()), 1.0);
  for (int round = 0; round < kHoldBackRounds; ++round) {
    const std::vector<double> steps = contact_->update_swept_vertex_steps(
        start, t0, start + held, t1, parameters_.ccd, layout_.t_free);
    bool cut = false;
    for (std::size_t v = 0; v < steps.size(); ++v)
      if (steps[v] < 1.0) {
        scale[v] *= kHeldFraction * steps[v];
        cut = true;
      }
    if (!cut) break;
    grade_down(scale, contact_->mesh().garment_edges, start, fade_length);
    for (Eigen::Index v = 0; v < motion.rows(); ++v)
      held.row(v) = scale[static_cast<std::size_t>(v)] * motion.row(v);
  }
  dx = layout_.pack(dt, held);
}

double GarmentProblem::step_length(const Eigen::VectorXd& dx) const {
  const auto motion = layout_.garment(dx);
  double length = motion.rows() > 0 ? motion.rowwise().norm().maxCoeff() : 0.0;
  if (layout_.t_free)
    length = std::max(length, std::abs(layout_.t(dx)) * contact_->max_displacement());
  return length;
}

bool GarmentProblem::is_valid_snapping(const Eigen::VectorXd& x) {
  const auto V = layout_.garment(x);
  const double t = layout_.t(x);
  const double step = contact_->update_swept_candidates(V, t, V, 1.0, parameters_.ccd);
  contact_->update_candidates(V, t);
  return step >= 1.0;
}

bool GarmentProblem::goal_reached(const Eigen::VectorXd& x) {
  if (!layout_.t_free) return false;
  return 1.0 - layout_.t(x) <= snap_window() && is_valid_snapping(x);
}

double GarmentProblem::minimum_distance(const Eigen::VectorXd& x) {
  contact_->update_candidates(layout_.garment(x), layout_.t(x));
  return contact_->minimum_distance(layout_.garment(x), layout_.t(x));
}

int pressed_tangle_pairs(const GarmentScene& scene, const RetargetParameters& parameters,
                         const Eigen::Ref<const MatrixX3d>& garment, double gap) {
  if (scene.garment_tangles.empty()) return 0;
  const ContactMesh mesh = contact_mesh_for(scene, parameters);
  const std::vector<std::array<int, 5>> close = tangled_pairs_closer_than(mesh, garment, gap);
  const std::vector<std::array<int, 5>>& unmodelled = mesh.unmodelled_self_pairs;
  return static_cast<int>(std::count_if(close.begin(), close.end(), [&](const auto& key) {
    return !std::binary_search(unmodelled.begin(), unmodelled.end(), key);
  }));
}

}  // namespace gr
