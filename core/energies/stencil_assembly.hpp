#pragma once

#include <algorithm>
#include <array>
#include <vector>

#include <tbb/parallel_for.h>
#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "core/common/psd_projection.hpp"

namespace gr {

/// Global indices of an element's K local degrees of freedom; -1 marks a fixed one (its
/// derivatives are dropped).
template <int K>
using StencilDofs = std::array<int, K>;

/// Assembles per-element values, K-gradients and K×K Hessians of one energy term into a
/// global value, gradient and sparse Hessian. The element list is fixed at construction,
/// so the Hessian's sparsity pattern and each element entry's slot in it are computed once;
/// a Hessian assembly only writes values. Elements are evaluated in parallel (TBB) into
/// per-element storage and summed in element order, so results do not depend on the
/// thread count. One assembly object is not safe to use from two threads at once (it
/// keeps its per-element scratch). A term over a fixed element list reaches it through
/// StencilTerm (core/energies/stencil_term.hpp).
template <int K>
class StencilAssembly {
 public:
  using LocalVector = Eigen::Matrix<double, K, 1>;
  using LocalMatrix = Eigen::Matrix<double, K, K>;

  StencilAssembly() = default;

  /// @param dofs per element, its K global dof indices in [0, dof_count) or -1.
  StencilAssembly(std::vector<StencilDofs<K>> dofs, int dof_count)
      : dofs_(std::move(dofs)), dof_count_(dof_count) {
    build_pattern();
  }

  int element_count() const { return static_cast<int>(dofs_.size()); }
  int dof_count() const { return dof_count_; }
  const StencilDofs<K>& dofs(int element) const { return dofs_[static_cast<std::size_t>(element)]; }

  /// Sum over elements of `element_value(e)` (a double).
  template <typename ValueFn>
  double value(ValueFn element_value) const {
    values_.resize(dofs_.size());
    tbb::parallel_for(0, element_count(), [&](int e) { values_[e] = element_value(e); });
    double sum = 0.0;
    for (double v : values_) sum += v;
    return sum;
  }

  /// Global gradient (resized to dof_count and overwritten) from
  /// `element_gradient(e, LocalVector& g)`, which returns the element's value.
  /// @return the total value.
  template <typename GradientFn>
  double gradient(GradientFn element_gradient, Eigen::VectorXd& gradient) const {
    values_.resize(dofs_.size());
    local_gradients_.resize(dofs_.size());
    tbb::parallel_for(0, element_count(), [&](int e) {
      local_gradients_[e].setZero();
      values_[e] = element_gradient(e, local_gradients_[e]);
    });
    gradient.setZero(dof_count_);
    double sum = 0.0;
    for (std::size_t e = 0; e < dofs_.size(); ++e) {
      sum += values_[e];
      for (int a = 0; a < K; ++a)
        if (dofs_[e][a] >= 0) gradient[dofs_[e][a]] += local_gradients_[e][a];
    }
    return sum;
  }

  /// Global Hessian (dof_count × dof_count, full symmetric storage) from
  /// `element_hessian(e, LocalMatrix& h)`; each element block projected to PSD first when
  /// `project_psd`. The pattern holds every element entry and the whole diagonal, whatever
  /// the values, so it is the same on every call.
  template <typename HessianFn>
  const Eigen::SparseMatrix<double>& hessian(HessianFn element_hessian, bool project_psd) const {
    local_hessians_.resize(dofs_.size());
    tbb::parallel_for(0, element_count(), [&](int e) {
      LocalMatrix& h = local_hessians_[e];
      h.setZero();
      element_hessian(e, h);
      if (project_psd) h = project_to_psd(h);
    });
    double* values = hessian_.valuePtr();
    std::fill(values, values + hessian_.nonZeros(), 0.0);
    const int* slot = slots_.data();
    for (std::size_t e = 0; e < dofs_.size(); ++e) {
      const LocalMatrix& h = local_hessians_[e];
      for (int b = 0; b < K; ++b)
        for (int a = 0; a < K; ++a, ++slot)
          if (*slot >= 0) values[*slot] += h(a, b);
    }
    return hessian_;
  }

 private:
  void build_pattern() {
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(dofs_.size() * K * K + static_cast<std::size_t>(dof_count_));
    for (int i = 0; i < dof_count_; ++i) entries.emplace_back(i, i, 0.0);
    for (const auto& d : dofs_)
      for (int b = 0; b < K; ++b)
        for (int a = 0; a < K; ++a)
          if (d[a] >= 0 && d[b] >= 0) entries.emplace_back(d[a], d[b], 0.0);
    hessian_.resize(dof_count_, dof_count_);
    hessian_.setFromTriplets(entries.begin(), entries.end());
    hessian_.makeCompressed();

    slots_.assign(dofs_.size() * K * K, -1);
    const int* outer = hessian_.outerIndexPtr();
    const int* inner = hessian_.innerIndexPtr();
    std::size_t k = 0;
    for (const auto& d : dofs_)
      for (int b = 0; b < K; ++b)
        for (int a = 0; a < K; ++a, ++k) {
          if (d[a] < 0 || d[b] < 0) continue;
          const int* first = inner + outer[d[b]];
          const int* last = inner + outer[d[b] + 1];
          slots_[k] = static_cast<int>(std::lower_bound(first, last, d[a]) - inner);
        }
  }

  std::vector<StencilDofs<K>> dofs_;
  int dof_count_ = 0;
  std::vector<int> slots_;  ///< per element, K×K column-major: index into hessian_'s values
  mutable Eigen::SparseMatrix<double> hessian_;
  mutable std::vector<double> values_;
  mutable std::vector<LocalVector> local_gradients_;
  mutable std::vector<LocalMatrix> local_hessians_;
};

}  // namespace gr
