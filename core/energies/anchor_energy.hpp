#pragma once

#include <vector>

#include "core/energies/stencil_term.hpp"

namespace gr {

/// Anchor: holds chosen garment vertices near their rest places. The energy is
/// 1/2 sum_v m_v |x_v - r_v|^2 over the anchored vertices v with rest places r_v and
/// weights m_v (1 unless given). Two uses: boundary loops (unweighted, "anchor", the
/// skeleton-free counterpart of L_pos) and every vertex weighted by its share of the
/// garment's area ("tether", a mass-like pull to the input that gives a free-floating
/// garment a unique place). Units: length^2 (times the weights' unit) in normalized scene
/// units; the caller multiplies by the term's weight.
class AnchorEnergy : public StencilTerm<AnchorEnergy, 3> {
 public:
  /// One anchored vertex; its stencil is x, y, z of the vertex.
  struct Element {
    int vertex;
    double weight;  ///< m_v >= 0
    Vector3d rest;  ///< r_v
  };

  /// @param rest garment rest positions (#Vg×3).
  /// @param vertices the anchored vertex ids, each in [0, #Vg) (repeats count twice).
  /// @param weights one non-negative finite weight per entry of `vertices`, or empty (all 1).
  /// @param name the term's name in reports.
  /// @throws std::invalid_argument on an id out of range, or weights of another size or
  ///         negative or not finite.
  AnchorEnergy(const Eigen::Ref<const MatrixX3d>& rest, const std::vector<int>& vertices,
               const DofLayout& layout, std::vector<double> weights = {},
               const char* name = "anchor");

  /// In the order of the constructor's `vertices`.
  const std::vector<Element>& elements() const { return elements_; }
  /// Moves every anchored vertex's rest place to its row of `positions` (#Vg×3).
  void set_rest(const Eigen::Ref<const MatrixX3d>& positions);

  const char* name() const override { return name_; }

  static StencilDofs<kStencilSize> element_dofs(const Element& element, const DofLayout& layout);
  /// q = x_v from garment positions V (#Vg×3); t plays no part.
  static LocalVector gather(const Element& element, const Eigen::Ref<const MatrixX3d>& V, double t);
  static double element_value(const Element& element, const LocalVector& q);
  static double element_gradient(const Element& element, const LocalVector& q, LocalVector& g);
  /// m_v times the identity (already PSD, so `project_psd` changes nothing).
  static void element_hessian(const Element& element, const LocalVector& q, bool project_psd,
                              LocalMatrix& h);
  static constexpr HessianProjection kProjection = HessianProjection::closed_form;

 private:
  std::vector<Element> elements_;
  const char* name_;
};

/// Each vertex's share of the area of `faces` (#F×3) over `vertices` (#V×3): a third of
/// the area of every face it is a corner of (the lumped mass on a unit-density sheet).
std::vector<double> vertex_area_shares(const Eigen::Ref<const MatrixX3d>& vertices,
                                       const Eigen::Ref<const MatrixX3i>& faces);

/// The vertices of every boundary loop of `faces` (#F×3), each once, in loop order.
std::vector<int> boundary_loop_vertices(const Eigen::Ref<const MatrixX3i>& faces);

}  // namespace gr
