#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "core/common/types.hpp"
#include "core/energies/dof_layout.hpp"
#include "core/energies/energy_term.hpp"
#include "core/energies/stencil_assembly.hpp"

namespace gr {

/// How a stencil term's element Hessians are made positive semi-definite.
enum class HessianProjection {
  /// `element_hessian` itself returns a PSD block when asked: the block is PSD anyway, or
  /// its projection is known in closed form.
  closed_form,
  /// `element_hessian` returns the exact block; the assembly projects it (project_to_psd,
  /// an eigen-decomposition per element) when asked.
  generic,
};

/// The dofs of `vertices`' coordinates, vertex by vertex (x, y, z of the first, then of the
/// next), in the first 3N entries of a K-stencil; entries past 3N are -1 (fixed) for the
/// caller to fill.
/// @pre 3N <= K, every vertex id in [0, layout.garment_vertex_count).
template <int K, std::size_t N>
StencilDofs<K> vertex_dofs(const std::array<int, N>& vertices, const DofLayout& layout) {
  static_assert(3 * static_cast<int>(N) <= K, "the vertices do not fit the stencil");
  StencilDofs<K> dofs;
  dofs.fill(-1);
  for (std::size_t v = 0; v < N; ++v)
    for (int axis = 0; axis < 3; ++axis)
      dofs[3 * v + static_cast<std::size_t>(axis)] = layout.vertex_dof(vertices[v], axis);
  return dofs;
}

/// An energy term that is a sum over a list of elements, each a function of K of the
/// solver's unknowns (its stencil). The term states the local pieces; this base sums them
/// with StencilAssembly, once for every term, so that the evaluation order (each element
/// alone, then the sum in element order) is the same for all of them.
///
/// Derived (CRTP: `class MyTerm : public StencilTerm<MyTerm, K>`) provides, with
/// LocalVector = Eigen::Matrix<double, K, 1> and LocalMatrix its K×K, all static but
/// elements():
///   - `Element`, and the member `const std::vector<Element>& elements() const`: the
///     element list, in summation order;
///   - `StencilDofs<K> element_dofs(const Element&, const DofLayout&)`: the element's K
///     global dofs, -1 for one the layout fixes (its derivatives are dropped);
///   - `LocalVector gather(const Element&, const Eigen::Ref<const MatrixX3d>& V, double t)`:
///     the element's local coordinates q, in its dofs' order, from the garment vertices V
///     (#Vg×3) and the avatar parameter t (read only by terms that depend on t);
///   - `double element_value(const Element&, const LocalVector& q)`;
///   - `double element_gradient(const Element&, const LocalVector& q, LocalVector& g)`:
///     writes dE/dq into g (zero on entry) and returns the element's value;
///   - `void element_hessian(const Element&, const LocalVector& q, bool project_psd,
///     LocalMatrix& h)`: writes d²E/dq² into h (zero on entry), made PSD when
///     `project_psd` and kProjection is closed_form;
///   - `static constexpr HessianProjection kProjection`.
/// Derived's constructor fills its element list and then calls build_stencils.
/// Not safe for concurrent use (the assembly keeps per-element scratch).
template <typename Derived, int K>
class StencilTerm : public EnergyTerm {
 public:
  static constexpr int kStencilSize = K;
  using LocalVector = Eigen::Matrix<double, K, 1>;
  using LocalMatrix = Eigen::Matrix<double, K, K>;

  /// Sum of element_value over the elements at garment positions V (#Vg×3) and t.
  double value(const Eigen::Ref<const MatrixX3d>& V, double t) const final {
    const auto& elements = derived().elements();
    return assembly_.value([&](int e) {
      const auto& element = elements[static_cast<std::size_t>(e)];
      return Derived::element_value(element, Derived::gather(element, V, t));
    });
  }

  /// Gradient over x (layout.dof_count()), resized and overwritten.
  void gradient(const Eigen::Ref<const MatrixX3d>& V, double t,
                Eigen::VectorXd& gradient) const final {
    const auto& elements = derived().elements();
    assembly_.gradient(
        [&](int e, LocalVector& g) {
          const auto& element = elements[static_cast<std::size_t>(e)];
          return Derived::element_gradient(element, Derived::gather(element, V, t), g);
        },
        gradient);
  }

  /// Hessian over x; with `project_psd` every element block is PSD (see kProjection), so
  /// the sum is too. The reference stays valid until the next call.
  const Eigen::SparseMatrix<double>& hessian(const Eigen::Ref<const MatrixX3d>& V, double t,
                                             bool project_psd) const final {
    const auto& elements = derived().elements();
    return assembly_.hessian(
        [&](int e, LocalMatrix& h) {
          const auto& element = elements[static_cast<std::size_t>(e)];
          Derived::element_hessian(element, Derived::gather(element, V, t), project_psd, h);
        },
        project_psd && Derived::kProjection == HessianProjection::generic);
  }

 protected:
  StencilTerm() = default;

  /// Builds the assembly (dofs and Hessian pattern) from the current element list. Called
  /// again after the list changes, it rebuilds the pattern: a term that does so between
  /// Hessians must say so in fixed_pattern().
  void build_stencils(const DofLayout& layout) {
    const auto& elements = derived().elements();
    std::vector<StencilDofs<K>> dofs;
    dofs.reserve(elements.size());
    for (const auto& element : elements) dofs.push_back(Derived::element_dofs(element, layout));
    assembly_ = StencilAssembly<K>(std::move(dofs), layout.dof_count());
  }

 private:
  const Derived& derived() const { return static_cast<const Derived&>(*this); }

  StencilAssembly<K> assembly_;
};

}  // namespace gr
