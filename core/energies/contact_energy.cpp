#include "core/energies/contact_energy.hpp"

#include <vector>

namespace gr {
namespace {

MatrixX3d stack_rows(const Eigen::Ref<const MatrixX3d>& top,
                     const Eigen::Ref<const MatrixX3d>& bottom) {
  MatrixX3d V(top.rows() + bottom.rows(), 3);
  V.topRows(top.rows()) = top;
  V.bottomRows(bottom.rows()) = bottom;
  return V;
}

}  // namespace

ContactEnergy::ContactEnergy(ContactMesh mesh, const Eigen::Ref<const MatrixX3d>& garment_rest,
                             const Eigen::Ref<const MatrixX3d>& avatar_start,
                             const Eigen::Ref<const MatrixX3d>& avatar_end, double dhat,
                             const DofLayout& layout)
    : finder_(std::move(mesh)), barrier_(dhat, stack_rows(garment_rest, avatar_end)),
      layout_(layout), avatar_start_(avatar_start), displacement_(avatar_end - avatar_start) {
  max_displacement_ = displacement_.rows() > 0 ? displacement_.rowwise().norm().maxCoeff() : 0.0;
  const int garment_coordinates = 3 * finder_.mesh().garment_vertex_count;
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<std::size_t>(garment_coordinates + displacement_.size()));
  for (int v = 0; v < finder_.mesh().garment_vertex_count; ++v)
    for (int axis = 0; axis < 3; ++axis)
      entries.emplace_back(3 * v + axis, layout_.vertex_dof(v, axis), 1.0);
  if (layout_.t_free)
    for (int a = 0; a < finder_.mesh().avatar_vertex_count; ++a)
      for (int axis = 0; axis < 3; ++axis)
        entries.emplace_back(garment_coordinates + 3 * a + axis, layout_.t_index(),
                             displacement_(a, axis));
  jacobian_.resize(3 * finder_.mesh().vertex_count(), layout_.dof_count());
  jacobian_.setFromTriplets(entries.begin(), entries.end());
  jacobian_transpose_ = jacobian_.transpose();
}

const MatrixX3d& ContactEnergy::stacked(const Eigen::Ref<const MatrixX3d>& V, double t) const {
  stacked_.resize(mesh().vertex_count(), 3);
  stacked_.topRows(mesh().garment_vertex_count) = V;
  stacked_.bottomRows(mesh().avatar_vertex_count) = avatar_start_ + t * displacement_;
  return stacked_;
}

void ContactEnergy::update_candidates(const Eigen::Ref<const MatrixX3d>& V, double t) {
  candidates_ = finder_.find(stacked(V, t), barrier_.dhat());
}

double ContactEnergy::update_swept_candidates(const Eigen::Ref<const MatrixX3d>& V0, double t0,
                                              const Eigen::Ref<const MatrixX3d>& V1, double t1,
                                              const CcdOptions& ccd) {
  const MatrixX3d start = stacked(V0, t0);
  const MatrixX3d& end = stacked(V1, t1);
  candidates_ = finder_.find_swept(start, end, barrier_.dhat());
  return max_step(candidates_, start, end, ccd);
}

std::vector<double> ContactEnergy::update_swept_vertex_steps(const Eigen::Ref<const MatrixX3d>& V0,
                                                             double t0,
                                                             const Eigen::Ref<const MatrixX3d>& V1,
                                                             double t1, const CcdOptions& ccd,
                                                             bool self_only) {
  const MatrixX3d start = stacked(V0, t0);
  const MatrixX3d& end = stacked(V1, t1);
  candidates_ = finder_.find_swept(start, end, barrier_.dhat());
  if (!self_only) {
    std::vector<double> steps = vertex_steps(candidates_, start, end, ccd);
    steps.resize(static_cast<std::size_t>(V0.rows()));
    return steps;
  }
  // The avatar's rows follow the garment's.
  const auto garment = [n = static_cast<int>(V0.rows())](int v) { return v < n; };
  Candidates self;
  for (const PointTriangleCandidate& c : candidates_.point_triangle)
    if (garment(c.point) && garment(c.triangle[0])) self.point_triangle.push_back(c);
  for (const EdgeEdgeCandidate& c : candidates_.edge_edge)
    if (garment(c.edge_a[0]) && garment(c.edge_b[0])) self.edge_edge.push_back(c);
  std::vector<double> steps = vertex_steps(self, start, end, ccd);
  steps.resize(static_cast<std::size_t>(V0.rows()));
  return steps;
}

double ContactEnergy::value(const Eigen::Ref<const MatrixX3d>& V, double t) const {
  return barrier_.value(candidates_, stacked(V, t));
}

void ContactEnergy::gradient(const Eigen::Ref<const MatrixX3d>& V, double t,
                             Eigen::VectorXd& gradient) const {
  gradient = jacobian_transpose_ * barrier_.gradient(candidates_, stacked(V, t));
}

const Eigen::SparseMatrix<double>& ContactEnergy::hessian(const Eigen::Ref<const MatrixX3d>& V,
                                                          double t, bool project_psd) const {
  const Eigen::SparseMatrix<double> H = barrier_.hessian(candidates_, stacked(V, t), project_psd);
  hessian_ = jacobian_transpose_ * (H * jacobian_);
  hessian_.makeCompressed();
  return hessian_;
}

double ContactEnergy::minimum_distance(const Eigen::Ref<const MatrixX3d>& V, double t) const {
  return barrier_.minimum_distance(candidates_, stacked(V, t));
}

}  // namespace gr
