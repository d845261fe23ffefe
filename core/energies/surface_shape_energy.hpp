#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "core/energies/stencil_term.hpp"

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
class SurfaceShapeEnergy : public StencilTerm<SurfaceShapeEnergy, 12> {
 public:
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
  const char* name() const override { return "surface"; }

  static StencilDofs<kStencilSize> element_dofs(const Element& element, const DofLayout& layout);
  /// q = (x0, x1, x2, x3) from garment positions V (#Vg×3); t plays no part.
  static LocalVector gather(const Element& element, const Eigen::Ref<const MatrixX3d>& V, double t);
  /// Per-element pieces on local coordinates q = (x0, x1, x2, x3).
  static double element_value(const Element& element, const LocalVector& q);
  static double element_gradient(const Element& element, const LocalVector& q, LocalVector& g);
  /// With `project_psd` the Hessian is made PSD in closed form: it is JᵀJ (Gauss–Newton,
  /// PSD) plus a second-order part linear in the residual, whose spectrum is known, so the
  /// element keeps JᵀJ plus that part's positive half. The result lies above the exact
  /// Hessian by a rank-two term no larger than the second-order part. Where that part is
  /// below 1e-3 of JᵀJ (Frobenius norms) it is dropped.
  static void element_hessian(const Element& element, const LocalVector& q, bool project_psd,
                              LocalMatrix& h);
  /// Projected in element_hessian, on the 9 edge-vector coordinates.
  static constexpr HessianProjection kProjection = HessianProjection::closed_form;

 private:
  std::vector<Element> elements_;
};

}  // namespace gr
