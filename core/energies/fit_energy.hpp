#pragma once

#include <array>
#include <vector>

#include <Eigen/SparseCore>

#include "core/energies/distance_field.hpp"
#include "core/energies/dof_layout.hpp"
#include "core/energies/energy_term.hpp"
#include "core/energies/stencil_assembly.hpp"

namespace gr {

/// A symmetric quadrature rule on a triangle: barycentric points and weights summing to 1.
struct TriangleQuadrature {
  std::vector<Eigen::Vector3d> barycentric;
  std::vector<double> weights;

  /// Rules with 1 (centroid), 3 (degree 2) or 6 (degree 4) points.
  /// @throw std::invalid_argument for any other count.
  static TriangleQuadrature with_points(int count);
};

/// Per face of `faces` (#F×3), whether it fits: false for a no-fit face, one whose three
/// vertices are all in `no_fit` (vertex ids; ids outside [0, vertex_count) are ignored).
std::vector<bool> fit_face_mask(const Eigen::Ref<const MatrixX3i>& faces, int vertex_count,
                                const std::vector<int>& no_fit);

/// L_fit (unweighted): sum over fit faces f and quadrature points p of
/// rest_area_f · weight_p · r(p)^2 with r = phi(p) - d(p), phi the avatar's signed distance
/// (positive outside) and d the point's target distance from the avatar: the barycentric
/// mean of its face's per-vertex offsets (0 without offsets). A point with d > 0 is held at
/// its distance from both sides (the garment keeps its ease); a point with d = 0 is only
/// pulled in (r > 0), as the barrier keeps it outside. A face is no-fit, and left out,
/// when its three vertices are all listed.
/// Units: area × length^2 in normalized scene units; the caller multiplies by w_fit.
/// The Hessian at a point it counts is 2 (∇phi ∇phiᵀ + r ∇²phi) ⊗ (b bᵀ) for the point's
/// barycentric weights b; with `project_psd` the 3×3 factor is projected to PSD (then the
/// Kronecker product, and the face's sum, are PSD too).
/// The distance field is sampled once per point for the gradient and the Hessian: the
/// samples (value, gradient, Hessian of phi) taken for one are kept for the other, and for
/// the value, while the positions stay the same (the solver asks for all three at each
/// Newton iterate). Not safe for concurrent use.
/// Not a StencilTerm: a face's energy is not a function of its gathered corners alone but
/// of field samples, which are taken for all faces at once and shared between calls; it
/// sums its faces with StencilAssembly itself.
class FitEnergy : public EnergyTerm {
 public:
  static constexpr int kStencilSize = 9;
  using LocalVector = Eigen::Matrix<double, kStencilSize, 1>;
  using LocalMatrix = Eigen::Matrix<double, kStencilSize, kStencilSize>;

  /// @param rest garment rest positions (#Vg×3) and faces (#Fg×3), for the rest areas.
  /// @param no_fit garment vertex ids (any order, repeats allowed).
  /// @param field must outlive this object; called from many threads at once.
  /// @param samples_per_face 1, 3 or 6.
  /// @param offsets per garment vertex (#Vg, normalized units, >= 0): the distance from the
  ///        avatar the fit holds it at; empty: 0 everywhere (the tight fit).
  /// @throw std::invalid_argument for another sample count, or offsets of another size.
  FitEnergy(const TriangleMesh& rest, const std::vector<int>& no_fit, const DistanceField& field,
            int samples_per_face, const DofLayout& layout, const std::vector<double>& offsets = {});

  /// Number of faces that fit (not no-fit).
  int fit_face_count() const { return static_cast<int>(faces_.size()); }

  const char* name() const override { return "fit"; }
  /// At garment positions V (#Vg×3); t plays no part.
  double value(const Eigen::Ref<const MatrixX3d>& V, double t) const override;
  void gradient(const Eigen::Ref<const MatrixX3d>& V, double t,
                Eigen::VectorXd& gradient) const override;
  const Eigen::SparseMatrix<double>& hessian(const Eigen::Ref<const MatrixX3d>& V, double t,
                                             bool project_psd) const override;

 private:
  /// phi and its derivatives at one quadrature point.
  struct Sample {
    double phi = 0.0;
    Vector3d gradient = Vector3d::Zero();
    Eigen::Matrix3d hessian = Eigen::Matrix3d::Zero();
  };

  /// Value of one face and, when the pointers are not null, its gradient and Hessian; from
  /// `samples` (the face's quadrature points) when not null, else from the field.
  double element(int face, const Eigen::Ref<const MatrixX3d>& V, const Sample* samples,
                 LocalVector* g, LocalMatrix* h, bool project_psd) const;
  /// The samples at V, taken now unless they were taken at V last time.
  const std::vector<Sample>& samples_at(const Eigen::Ref<const MatrixX3d>& V) const;
  bool has_samples_at(const Eigen::Ref<const MatrixX3d>& V) const;
  /// Quadrature point q of face f at V.
  Vector3d point(int face, std::size_t q, const Eigen::Ref<const MatrixX3d>& V) const;

  std::vector<std::array<int, 3>> faces_;
  std::vector<double> rest_areas_;
  std::vector<double> offsets_;  ///< per garment vertex; empty: all 0
  const DistanceField* field_;
  TriangleQuadrature quadrature_;
  StencilAssembly<kStencilSize> assembly_;
  mutable std::vector<Sample> samples_;  ///< per face, per quadrature point
  mutable MatrixX3d sampled_positions_;  ///< where samples_ were taken (empty: nowhere yet)
};

}  // namespace gr
