#pragma once

#include <array>
#include <vector>

#include "core/energies/stencil_term.hpp"

namespace gr {

/// Edge stretch (unweighted): keeps the garment's edge lengths, and so its size, where
/// nothing else sets it (no skeletons). For every edge (x_i, x_j) with rest length L and
/// deformed length l = |x_i - x_j|, the energy is sum_e w_e (l - L)^2 / L with
/// w_e = A_e / L and A_e a third of the rest areas of the faces next to the edge, so the
/// sum approximates the integral of the squared strain over the rest surface and does
/// not grow with the mesh's resolution. Units: area in normalized scene units (strain is
/// dimensionless); the caller multiplies by w_stretch. Unlike L_surf it resists uniform
/// scaling.
class StretchEnergy : public StencilTerm<StretchEnergy, 6> {
 public:
  /// One edge; its stencil is x_i, then x_j.
  struct Element {
    std::array<int, 2> vertices;
    double rest_length;  ///< L > 0
    double weight;       ///< w_e / L = A_e / L^2, the factor in front of (l - L)^2
  };

  /// @param rest garment rest positions (#Vg×3) and faces (#Fg×3).
  /// Edges of zero rest length (duplicate vertices) or zero adjacent rest area are left
  /// out: no strain is defined on them.
  StretchEnergy(const TriangleMesh& rest, const DofLayout& layout);

  const std::vector<Element>& elements() const { return elements_; }
  const char* name() const override { return "stretch"; }

  static StencilDofs<kStencilSize> element_dofs(const Element& element, const DofLayout& layout);
  /// q = (x_i, x_j) from V (#Vg×3); t plays no part.
  static LocalVector gather(const Element& element, const Eigen::Ref<const MatrixX3d>& V, double t);
  /// One edge's energy, gradient and Hessian at q = (x_i, x_j). At l = 0 the energy is
  /// not differentiable; gradient and Hessian are taken as zero there.
  static double element_value(const Element& element, const LocalVector& q);
  static double element_gradient(const Element& element, const LocalVector& q, LocalVector& g);
  /// Exact Hessian; with `project_psd` the block keeps its positive part in closed form
  /// (the transverse stiffness of a compressed edge, negative, is set to zero). That is
  /// the exact projection: the block's eigenvalues are 4w and 4w (l - L) / l twice, and
  /// zero.
  static void element_hessian(const Element& element, const LocalVector& q, bool project_psd,
                              LocalMatrix& h);
  static constexpr HessianProjection kProjection = HessianProjection::closed_form;

 private:
  std::vector<Element> elements_;
};

}  // namespace gr
