#pragma once

#include <array>
#include <vector>

#include <Eigen/SparseCore>

#include "core/energies/dof_layout.hpp"
#include "core/energies/energy_term.hpp"
#include "core/energies/stencil_assembly.hpp"

namespace gr {

/// Tie: holds pairs of garment vertices together, 1/2 sum |x_a - x_b|^2 over the pairs.
/// A non-manifold edge is split into copies of its vertices so that every edge has at most
/// two faces; the ties keep each copy on its original, and the written file welds them
/// back. Units: length^2 in normalized scene units; the caller multiplies by the weight.
class TieEnergy : public EnergyTerm {
 public:
  static constexpr int kStencilSize = 6;
  using LocalVector = Eigen::Matrix<double, kStencilSize, 1>;
  using LocalMatrix = Eigen::Matrix<double, kStencilSize, kStencilSize>;

  /// @param pairs vertex pairs (a, b), each id in [0, layout's vertex count).
  /// @throw std::invalid_argument on an id out of range or a vertex tied to itself.
  TieEnergy(std::vector<std::array<int, 2>> pairs, const DofLayout& layout);

  const char* name() const override { return "tie"; }
  double value(const Eigen::Ref<const MatrixX3d>& V, double t) const override;
  void gradient(const Eigen::Ref<const MatrixX3d>& V, double t,
                Eigen::VectorXd& gradient) const override;
  /// [I -I; -I I] per pair (already PSD).
  const Eigen::SparseMatrix<double>& hessian(const Eigen::Ref<const MatrixX3d>& V, double t,
                                             bool project_psd) const override;

 private:
  std::vector<std::array<int, 2>> pairs_;
  StencilAssembly<kStencilSize> assembly_;
};

}  // namespace gr
