#pragma once

#include <vector>

#include <Eigen/SparseCore>

#include "core/energies/dof_layout.hpp"
#include "core/energies/energy_term.hpp"
#include "core/energies/stencil_assembly.hpp"

namespace gr {

/// Anchor (unweighted): holds chosen garment vertices near their rest places, the
/// skeleton-free counterpart of L_pos for boundary loops. The energy is
/// 1/2 sum_v |x_v - r_v|^2 over the anchored vertices v with rest places r_v. Units:
/// length^2 in normalized scene units; the caller multiplies by w_anchor.
class AnchorEnergy : public EnergyTerm {
 public:
  static constexpr int kStencilSize = 3;
  using LocalVector = Eigen::Matrix<double, kStencilSize, 1>;
  using LocalMatrix = Eigen::Matrix<double, kStencilSize, kStencilSize>;

  /// @param rest garment rest positions (#Vg×3).
  /// @param vertices the anchored vertex ids, each in [0, #Vg) (repeats count twice).
  /// @throws std::invalid_argument on an id out of range.
  AnchorEnergy(const Eigen::Ref<const MatrixX3d>& rest, std::vector<int> vertices,
               const DofLayout& layout);

  const std::vector<int>& vertices() const { return vertices_; }

  const char* name() const override { return "anchor"; }
  double value(const Eigen::Ref<const MatrixX3d>& V, double t) const override;
  void gradient(const Eigen::Ref<const MatrixX3d>& V, double t,
                Eigen::VectorXd& gradient) const override;
  /// The identity on each anchored vertex (already PSD).
  const Eigen::SparseMatrix<double>& hessian(const Eigen::Ref<const MatrixX3d>& V, double t,
                                             bool project_psd) const override;

 private:
  std::vector<int> vertices_;
  MatrixX3d rest_;  ///< rest place of each anchored vertex, in vertices_' order
  StencilAssembly<kStencilSize> assembly_;
};

/// The vertices of every boundary loop of `faces` (#F×3), each once, in loop order.
std::vector<int> boundary_loop_vertices(const Eigen::Ref<const MatrixX3i>& faces);

}  // namespace gr
