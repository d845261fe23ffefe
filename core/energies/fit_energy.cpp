#include "core/energies/fit_energy.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include <tbb/parallel_for.h>

namespace gr {

TriangleQuadrature TriangleQuadrature::with_points(int count) {
  TriangleQuadrature rule;
  const auto add_orbit = [&rule](double a, double b, double weight) {
    // The three permutations of (a, b, b).
    rule.barycentric.emplace_back(a, b, b);
    rule.barycentric.emplace_back(b, a, b);
    rule.barycentric.emplace_back(b, b, a);
    rule.weights.insert(rule.weights.end(), 3, weight);
  };
  switch (count) {
    case 1:
      rule.barycentric.emplace_back(1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0);
      rule.weights.push_back(1.0);
      break;
    case 3: add_orbit(2.0 / 3.0, 1.0 / 6.0, 1.0 / 3.0); break;
    case 6:  // Strang and Fix / Dunavant degree-4 rule.
      add_orbit(0.108103018168070, 0.445948490915965, 0.223381589678011);
      add_orbit(0.816847572980459, 0.091576213509771, 0.109951743655322);
      break;
    default:
      throw std::invalid_argument("fit samples per face must be 1, 3 or 6, not " +
                                  std::to_string(count));
  }
  return rule;
}

std::vector<bool> fit_face_mask(const Eigen::Ref<const MatrixX3i>& faces, int vertex_count,
                                const std::vector<int>& no_fit) {
  std::vector<bool> listed(static_cast<std::size_t>(std::max(vertex_count, 0)), false);
  for (const int v : no_fit)
    if (v >= 0 && v < vertex_count) listed[static_cast<std::size_t>(v)] = true;
  std::vector<bool> fits(static_cast<std::size_t>(faces.rows()), true);
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    fits[static_cast<std::size_t>(f)] = !(listed[static_cast<std::size_t>(faces(f, 0))] &&
                                          listed[static_cast<std::size_t>(faces(f, 1))] &&
                                          listed[static_cast<std::size_t>(faces(f, 2))]);
  return fits;
}

FitEnergy::FitEnergy(const TriangleMesh& rest, const std::vector<int>& no_fit,
                     const DistanceField& field, int samples_per_face, const DofLayout& layout,
                     const std::vector<double>& offsets)
    : offsets_(offsets), field_(&field),
      quadrature_(TriangleQuadrature::with_points(samples_per_face)) {
  if (!offsets_.empty() && offsets_.size() != static_cast<std::size_t>(rest.vertices.rows()))
    throw std::invalid_argument("fit offsets: " + std::to_string(offsets_.size()) + " values for " +
                                std::to_string(rest.vertices.rows()) + " garment vertices");
  const std::vector<bool> fits =
      fit_face_mask(rest.faces, static_cast<int>(rest.vertices.rows()), no_fit);
  std::vector<StencilDofs<kStencilSize>> dofs;
  for (int f = 0; f < rest.faces.rows(); ++f) {
    if (!fits[static_cast<std::size_t>(f)]) continue;
    const std::array<int, 3> face = {rest.faces(f, 0), rest.faces(f, 1), rest.faces(f, 2)};
    const Vector3d a = rest.vertices.row(face[0]).transpose();
    const Vector3d b = rest.vertices.row(face[1]).transpose();
    const Vector3d c = rest.vertices.row(face[2]).transpose();
    faces_.push_back(face);
    rest_areas_.push_back(0.5 * (b - a).cross(c - a).norm());
    StencilDofs<kStencilSize> d;
    for (int v = 0; v < 3; ++v)
      for (int axis = 0; axis < 3; ++axis) d[3 * v + axis] = layout.vertex_dof(face[v], axis);
    dofs.push_back(d);
  }
  assembly_ = StencilAssembly<kStencilSize>(std::move(dofs), layout.dof_count());
}

Vector3d FitEnergy::point(int face, std::size_t q, const Eigen::Ref<const MatrixX3d>& V) const {
  const auto& f = faces_[static_cast<std::size_t>(face)];
  const Vector3d& b = quadrature_.barycentric[q];
  return b[0] * V.row(f[0]).transpose() + b[1] * V.row(f[1]).transpose() +
         b[2] * V.row(f[2]).transpose();
}

bool FitEnergy::has_samples_at(const Eigen::Ref<const MatrixX3d>& V) const {
  return sampled_positions_.rows() == V.rows() && sampled_positions_ == V;
}

const std::vector<FitEnergy::Sample>& FitEnergy::samples_at(
    const Eigen::Ref<const MatrixX3d>& V) const {
  if (has_samples_at(V)) return samples_;
  const std::size_t per_face = quadrature_.weights.size();
  samples_.resize(faces_.size() * per_face);
  tbb::parallel_for(0, fit_face_count(), [&](int face) {
    for (std::size_t q = 0; q < per_face; ++q) {
      Sample& s = samples_[static_cast<std::size_t>(face) * per_face + q];
      s.phi = field_->evaluate(point(face, q, V), &s.gradient, &s.hessian);
    }
  });
  sampled_positions_ = V;
  return samples_;
}

double FitEnergy::element(int face, const Eigen::Ref<const MatrixX3d>& V, const Sample* samples,
                          LocalVector* g, LocalMatrix* h, bool project_psd) const {
  const double area = rest_areas_[static_cast<std::size_t>(face)];
  const auto& corners = faces_[static_cast<std::size_t>(face)];
  double value = 0.0;
  for (std::size_t q = 0; q < quadrature_.weights.size(); ++q) {
    const Vector3d& b = quadrature_.barycentric[q];
    Sample fresh;
    if (!samples)
      fresh.phi = field_->evaluate(point(face, q, V), g || h ? &fresh.gradient : nullptr,
                                   h ? &fresh.hessian : nullptr);
    const Sample& sample = samples ? samples[q] : fresh;
    double target = 0.0;
    if (!offsets_.empty())
      for (int v = 0; v < 3; ++v) target += b[v] * offsets_[static_cast<std::size_t>(corners[v])];
    const double r = sample.phi - target;
    if (target <= 0.0 && r <= 0.0) continue;
    const Vector3d& grad_phi = sample.gradient;
    const double w = area * quadrature_.weights[q];
    value += w * r * r;
    if (g)
      for (int v = 0; v < 3; ++v) g->segment<3>(3 * v) += 2.0 * w * r * b[v] * grad_phi;
    if (h) {
      Eigen::Matrix3d point_hessian =
          2.0 * w * (grad_phi * grad_phi.transpose() + r * sample.hessian);
      if (project_psd) point_hessian = project_to_psd(point_hessian);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) h->block<3, 3>(3 * i, 3 * j) += b[i] * b[j] * point_hessian;
    }
  }
  return value;
}

double FitEnergy::value(const Eigen::Ref<const MatrixX3d>& V, double) const {
  // Line-search points are new each time: sampled for the value alone, not kept.
  const Sample* samples = has_samples_at(V) ? samples_.data() : nullptr;
  const std::size_t per_face = quadrature_.weights.size();
  return assembly_.value([&](int f) {
    return element(f, V, samples ? samples + static_cast<std::size_t>(f) * per_face : nullptr,
                   nullptr, nullptr, false);
  });
}

void FitEnergy::gradient(const Eigen::Ref<const MatrixX3d>& V, double,
                         Eigen::VectorXd& gradient) const {
  const Sample* samples = samples_at(V).data();
  const std::size_t per_face = quadrature_.weights.size();
  assembly_.gradient(
      [&](int f, LocalVector& g) {
        return element(f, V, samples + static_cast<std::size_t>(f) * per_face, &g, nullptr, false);
      },
      gradient);
}

const Eigen::SparseMatrix<double>& FitEnergy::hessian(const Eigen::Ref<const MatrixX3d>& V, double,
                                                      bool project_psd) const {
  const Sample* samples = samples_at(V).data();
  const std::size_t per_face = quadrature_.weights.size();
  // The per-point projection already makes each block PSD; the assembly need not redo it.
  return assembly_.hessian(
      [&](int f, LocalMatrix& h) {
        element(f, V, samples + static_cast<std::size_t>(f) * per_face, nullptr, &h, project_psd);
      },
      false);
}

}  // namespace gr
