#pragma once

#include <array>
#include <vector>

#include "core/energies/stencil_term.hpp"

namespace gr {

/// A garment vertex carried by a triangle of another part of the garment: it keeps its
/// offset from the triangle's centroid.
struct Attachment {
  int vertex = 0;
  std::array<int, 3> triangle{};
  Vector3d offset = Vector3d::Zero();  ///< vertex minus the triangle's centroid at rest
};

/// Attachment: 1/2 sum |x_v - c(x_a, x_b, x_c) - offset|^2 over the attachments, c the
/// centroid. A piece laid on or through another (a belt through a dress, a pocket on a
/// shirt) keeps its place on the piece under it: their contact is not modelled where they
/// cross as given, so without it the piece could slide through. Units: length^2 in
/// normalized scene units; the caller multiplies by the weight.
class AttachmentEnergy : public StencilTerm<AttachmentEnergy, 12> {
 public:
  /// One attachment; its stencil is the vertex, then the triangle's three corners.
  using Element = Attachment;

  /// @throw std::invalid_argument when an id is outside the garment or the vertex is a
  ///        corner of its own triangle.
  AttachmentEnergy(std::vector<Attachment> attachments, const DofLayout& layout);

  const std::vector<Element>& elements() const { return attachments_; }
  const char* name() const override { return "attachment"; }

  static StencilDofs<kStencilSize> element_dofs(const Element& attachment, const DofLayout& layout);
  /// q = (x_v, x_a, x_b, x_c) from garment positions V (#Vg×3); t plays no part.
  static LocalVector gather(const Element& attachment, const Eigen::Ref<const MatrixX3d>& V,
                            double t);
  static double element_value(const Element& attachment, const LocalVector& q);
  static double element_gradient(const Element& attachment, const LocalVector& q, LocalVector& g);
  /// Jᵀ J with J = [I, -I/3, -I/3, -I/3] (already PSD, so `project_psd` changes nothing).
  static void element_hessian(const Element& attachment, const LocalVector& q, bool project_psd,
                              LocalMatrix& h);
  static constexpr HessianProjection kProjection = HessianProjection::closed_form;

 private:
  std::vector<Attachment> attachments_;
};

}  // namespace gr
