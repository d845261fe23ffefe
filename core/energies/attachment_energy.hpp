#pragma once

#include <array>
#include <vector>

#include <Eigen/SparseCore>

#include "core/energies/dof_layout.hpp"
#include "core/energies/energy_term.hpp"
#include "core/energies/stencil_assembly.hpp"

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
class AttachmentEnergy : public EnergyTerm {
 public:
  static constexpr int kStencilSize = 12;
  using LocalVector = Eigen::Matrix<double, kStencilSize, 1>;
  using LocalMatrix = Eigen::Matrix<double, kStencilSize, kStencilSize>;

  /// @throw std::invalid_argument when an id is outside the garment or the vertex is a
  ///        corner of its own triangle.
  AttachmentEnergy(std::vector<Attachment> attachments, const DofLayout& layout);

  const char* name() const override { return "attachment"; }
  double value(const Eigen::Ref<const MatrixX3d>& V, double t) const override;
  void gradient(const Eigen::Ref<const MatrixX3d>& V, double t,
                Eigen::VectorXd& gradient) const override;
  /// Jᵀ J with J = [I, -I/3, -I/3, -I/3] per attachment (already PSD).
  const Eigen::SparseMatrix<double>& hessian(const Eigen::Ref<const MatrixX3d>& V, double t,
                                             bool project_psd) const override;

 private:
  Vector3d residual(const Attachment& a, const Eigen::Ref<const MatrixX3d>& V) const;

  std::vector<Attachment> attachments_;
  StencilAssembly<kStencilSize> assembly_;
};

}  // namespace gr
