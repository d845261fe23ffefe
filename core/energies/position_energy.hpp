#pragma once

#include <vector>

#include <Eigen/SparseCore>

#include "core/energies/dof_layout.hpp"
#include "core/energies/energy_term.hpp"
#include "core/energies/stencil_assembly.hpp"
#include "core/skeleton/loop_bones.hpp"

namespace gr {

/// L_pos (unweighted): boundary loops keep their relative position along their bone while
/// the skeleton moves with t. For a loop vertex x and its loop's bone (a(t), b(t)),
/// s(t, x) = (x - a)·(b - a) / |b - a|^2 is the parameter of x's projection on the bone
/// line; the energy is 1/2 sum (s(t, x) - s_rest)^2, s_rest taken at t = 0 on the initial
/// garment (so it is zero there). Dimensionless; the caller multiplies by w_pos.
/// Derivatives are with respect to the vertex and, when the layout frees it, t.
class PositionEnergy : public EnergyTerm {
 public:
  static constexpr int kStencilSize = 4;  ///< x, y, z of the vertex, then t
  using LocalVector = Eigen::Matrix<double, kStencilSize, 1>;
  using LocalMatrix = Eigen::Matrix<double, kStencilSize, kStencilSize>;

  struct Element {
    int vertex;
    MovingBone bone;
    double rest_parameter;  ///< s at t = 0 on the initial garment
  };

  /// @param initial garment vertices at t = 0 (#Vg×3).
  /// @param loops from assign_loop_bones; bones of zero length at t = 0 are left out.
  PositionEnergy(const Eigen::Ref<const MatrixX3d>& initial, const std::vector<LoopBone>& loops,
                 const DofLayout& layout);

  const std::vector<Element>& elements() const { return elements_; }

  const char* name() const override { return "position"; }
  double value(const Eigen::Ref<const MatrixX3d>& V, double t) const override;
  void gradient(const Eigen::Ref<const MatrixX3d>& V, double t,
                Eigen::VectorXd& gradient) const override;
  const Eigen::SparseMatrix<double>& hessian(const Eigen::Ref<const MatrixX3d>& V, double t,
                                             bool project_psd) const override;

  /// The bone parameter s(t, x) and, when asked, its gradient and Hessian in (x, t).
  static double bone_parameter(const MovingBone& bone, const LocalVector& q, LocalVector* gradient,
                               LocalMatrix* hessian);
  static double element_value(const Element& element, const LocalVector& q);
  static double element_gradient(const Element& element, const LocalVector& q, LocalVector& g);
  static void element_hessian(const Element& element, const LocalVector& q, LocalMatrix& h);

 private:
  LocalVector gather(int element, const Eigen::Ref<const MatrixX3d>& V, double t) const;

  std::vector<Element> elements_;
  StencilAssembly<kStencilSize> assembly_;
};

}  // namespace gr
