#pragma once

#include <array>
#include <vector>

#include <Eigen/SparseCore>

#include "core/energies/dof_layout.hpp"
#include "core/energies/energy_term.hpp"
#include "core/energies/stencil_assembly.hpp"

namespace gr {

/// L_surf: keeps the garment's surface shape. For every interior edge (x0, x1) with
/// opposite vertices x2 (first triangle) and x3 (second triangle), the vector w = x3 - x2
/// is written at rest in each triangle's frame, (e, u1, e × u1) and (e, u2, e × u2) with
/// e = x1 - x0, u1 = x2 - x0, u2 = x3 - x0 and the normal the unnormalized cross product.
/// Deformed, each frame reconstructs w from its rest coefficients (r1, r2); the energy is
/// sum_e weight_e |r1 - r2|^2 with weight_e a third of the two triangles' rest areas.
///
/// With the unnormalized normal r1 - r2 is a quadratic polynomial of the 12 coordinates,
/// so the Hessian is exact and cheap. The energy is zero for any rigid motion of the rest
/// shape; it is not invariant under uniform scaling (the normal scales quadratically).
/// Units: area × length^2 in normalized scene units.
class SurfaceShapeEnergy : public EnergyTerm {
 public:
  static constexpr int kStencilSize = 12;
  using LocalVector = Eigen::Matrix<double, kStencilSize, 1>;
  using LocalMatrix = Eigen::Matrix<double, kStencilSize, kStencilSize>;

  /// One interior edge, its two opposite vertices and rest data.
  struct Element {
    std::array<int, 4> vertices;          ///< x0, x1 (the edge), x2, x3 (opposite vertices)
    Eigen::Vector3d coefficients_first;   ///< w in the first triangle's rest frame
    Eigen::Vector3d coefficients_second;  ///< w in the second triangle's rest frame
    double weight;                        ///< (rest area 1 + rest area 2) / 3
  };

  /// @param rest garment rest positions (#Vg×3) and faces (#Fg×3).
  /// Edges with more than two incident faces and edges next to a rest triangle of
  /// (relative) zero area are left out: their frames are not defined.
  SurfaceShapeEnergy(const TriangleMesh& rest, const DofLayout& layout);

  const std::vector<Element>& elements() const { return elements_; }

  /// Energy at garment positions V (#Vg×3).
  const char* name() const override { return "surface"; }
  /// Energy at garment positions V (#Vg×3); t plays no part.
  double value(const Eigen::Ref<const MatrixX3d>& V, double t) const override;
  /// Gradient over x (layout.dof_count()), overwritten; returns the energy.
  void gradient(const Eigen::Ref<const MatrixX3d>& V, double t,
                Eigen::VectorXd& gradient) const override;
  /// Hessian over x. With `project_psd` each element's Hessian is made PSD in closed form:
  /// it is JᵀJ (Gauss–Newton, PSD) plus a second-order part linear in the residual, whose
  /// spectrum is known (see element_hessian), so the element keeps JᵀJ plus that part's
  /// positive half. The result lies above the exact Hessian by a rank-two term no larger
  /// than the second-order part. Where that part is below 1e-3 of JᵀJ (Frobenius norms)
  /// it is dropped.
  const Eigen::SparseMatrix<double>& hessian(const Eigen::Ref<const MatrixX3d>& V, double t,
                                             bool project_psd) const override;

  /// Per-element pieces on local coordinates q = (x0, x1, x2, x3).
  static double element_value(const Element& element, const LocalVector& q);
  static double element_gradient(const Element& element, const LocalVector& q, LocalVector& g);
  static void element_hessian(const Element& element, const LocalVector& q, LocalMatrix& h,
                              bool project_psd = false);

 private:
  LocalVector gather(int element, const Eigen::Ref<const MatrixX3d>& V) const;

  std::vector<Element> elements_;
  StencilAssembly<kStencilSize> assembly_;
};

}  // namespace gr
