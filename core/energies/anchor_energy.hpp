#pragma once

#include <vector>

#include <Eigen/SparseCore>

#include "core/energies/dof_layout.hpp"
#include "core/energies/energy_term.hpp"
#include "core/energies/stencil_assembly.hpp"

namespace gr {

/// Anchor: holds chosen garment vertices near their rest places. The energy is
/// 1/2 sum_v m_v |x_v - r_v|^2 over the anchored vertices v with rest places r_v and
/// weights m_v (1 unless given). Two uses: boundary loops (unweighted, "anchor", the
/// skeleton-free counterpart of L_pos) and every vertex weighted by its share of the
/// garment's area ("tether", a mass-like pull to the input that gives a free-floating
/// garment a unique place). Units: length^2 (times the weights' unit) in normalized scene
/// units; the caller multiplies by the term's weight.
class AnchorEnergy : public EnergyTerm {
 public:
  static constexpr int kStencilSize = 3;
  using LocalVector = Eigen::Matrix<double, kStencilSize, 1>;
  using LocalMatrix = Eigen::Matrix<double, kStencilSize, kStencilSize>;

  /// @param rest garment rest positions (#Vg×3).
  /// @param vertices the anchored vertex ids, each in [0, #Vg) (repeats count twice).
  /// @param weights one non-negative finite weight per entry of `vertices`, or empty (all 1).
  /// @param name the term's name in reports.
  /// @throws std::invalid_argument on an id out of range, or weights of another size or
  ///         negative or not finite.
  AnchorEnergy(const Eigen::Ref<const MatrixX3d>& rest, std::vector<int> vertices,
               const DofLayout& layout, std::vector<double> weights = {},
               const char* name = "anchor");

  const std::vector<int>& vertices() const { return vertices_; }
  /// Moves every anchored vertex's rest place to its row of `positions` (#Vg×3).
  void set_rest(const Eigen::Ref<const MatrixX3d>& positions);

  const char* name() const override { return name_; }
  double value(const Eigen::Ref<const MatrixX3d>& V, double t) const override;
  void gradient(const Eigen::Ref<const MatrixX3d>& V, double t,
                Eigen::VectorXd& gradient) const override;
  /// m_v times the identity on each anchored vertex (already PSD).
  const Eigen::SparseMatrix<double>& hessian(const Eigen::Ref<const MatrixX3d>& V, double t,
                                             bool project_psd) const override;

 private:
  std::vector<int> vertices_;
  std::vector<double> weights_;  ///< per entry of vertices_
  const char* name_;
  MatrixX3d rest_;  ///< rest place of each anchored vertex, in vertices_' order
  StencilAssembly<kStencilSize> assembly_;
};

/// Each vertex's share of the area of `faces` (#F×3) over `vertices` (#V×3): a third of
/// the area of every face it is a corner of (the lumped mass on a unit-density sheet).
std::vector<double> vertex_area_shares(const Eigen::Ref<const MatrixX3d>& vertices,
                                       const Eigen::Ref<const MatrixX3i>& faces);

/// The vertices of every boundary loop of `faces` (#F×3), each once, in loop order.
std::vector<int> boundary_loop_vertices(const Eigen::Ref<const MatrixX3i>& faces);

}  // namespace gr
