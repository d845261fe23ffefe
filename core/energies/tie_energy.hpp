#pragma once

#include <array>
#include <vector>

#include "core/energies/stencil_term.hpp"

namespace gr {

/// Tie: holds pairs of garment vertices together, 1/2 sum |x_a - x_b|^2 over the pairs.
/// A non-manifold edge is split into copies of its vertices so that every edge has at most
/// two faces; the ties keep each copy on its original, and the written file welds them
/// back. Units: length^2 in normalized scene units; the caller multiplies by the weight.
class TieEnergy : public StencilTerm<TieEnergy, 6> {
 public:
  /// A tied pair (a, b); its stencil is x_a, then x_b.
  using Element = std::array<int, 2>;

  /// @param pairs vertex pairs (a, b), each id in [0, layout's vertex count).
  /// @throw std::invalid_argument on an id out of range or a vertex tied to itself.
  TieEnergy(std::vector<Element> pairs, const DofLayout& layout);

  const std::vector<Element>& elements() const { return pairs_; }
  const char* name() const override { return "tie"; }

  static StencilDofs<kStencilSize> element_dofs(const Element& pair, const DofLayout& layout);
  /// q = (x_a, x_b) from garment positions V (#Vg×3); t plays no part.
  static LocalVector gather(const Element& pair, const Eigen::Ref<const MatrixX3d>& V, double t);
  static double element_value(const Element& pair, const LocalVector& q);
  static double element_gradient(const Element& pair, const LocalVector& q, LocalVector& g);
  /// [I -I; -I I] (already PSD, so `project_psd` changes nothing).
  static void element_hessian(const Element& pair, const LocalVector& q, bool project_psd,
                              LocalMatrix& h);
  static constexpr HessianProjection kProjection = HessianProjection::closed_form;

 private:
  std::vector<Element> pairs_;
};

}  // namespace gr
