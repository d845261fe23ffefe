#pragma once

#include <vector>

#include "core/energies/stencil_term.hpp"
#include "core/skeleton/loop_bones.hpp"

namespace gr {

/// L_pos (unweighted): boundary loops keep their relative position along their bone while
/// the skeleton moves with t. For a loop vertex x and its loop's bone (a(t), b(t)),
/// s(t, x) = (x - a)·(b - a) / |b - a|^2 is the parameter of x's projection on the bone
/// line; the energy is 1/2 sum (s(t, x) - s_rest)^2, s_rest taken at t = 0 on the initial
/// garment (so it is zero there). Dimensionless; the caller multiplies by w_pos.
/// Derivatives are with respect to the vertex and, when the layout frees it, t.
class PositionEnergy : public StencilTerm<PositionEnergy, 4> {
 public:
  /// One loop vertex; its stencil is x, y, z of the vertex, then t.
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

  /// The bone parameter s(t, x) and, when asked, its gradient and Hessian in (x, t).
  static double bone_parameter(const MovingBone& bone, const LocalVector& q, LocalVector* gradient,
                               LocalMatrix* hessian);

  /// The vertex's dofs, then t's (-1 when the layout fixes t).
  static StencilDofs<kStencilSize> element_dofs(const Element& element, const DofLayout& layout);
  /// q = (x, t) from garment positions V (#Vg×3) and t.
  static LocalVector gather(const Element& element, const Eigen::Ref<const MatrixX3d>& V, double t);
  static double element_value(const Element& element, const LocalVector& q);
  static double element_gradient(const Element& element, const LocalVector& q, LocalVector& g);
  /// Exact Hessian, whatever `project_psd`: the assembly projects it.
  static void element_hessian(const Element& element, const LocalVector& q, bool project_psd,
                              LocalMatrix& h);
  static constexpr HessianProjection kProjection = HessianProjection::generic;

 private:
  std::vector<Element> elements_;
};

}  // namespace gr
