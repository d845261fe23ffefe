#pragma once

#include <Eigen/SparseCore>

#include "core/common/types.hpp"

namespace gr {

/// One term of a garment objective, unweighted, as the problem sums it: value, gradient
/// and Hessian on the same arguments, the garment vertices V (#Vg×3, normalized scene
/// units) and the avatar parameter t (ignored by terms that do not depend on it).
/// Derivatives are over the solver's unknowns x (DofLayout::dof_count()): a term built
/// with a layout that fixes t has no t entries.
class EnergyTerm {
 public:
  virtual ~EnergyTerm() = default;

  /// The term's key in reports ("surface", "contact", ...).
  virtual const char* name() const = 0;
  virtual double value(const Eigen::Ref<const MatrixX3d>& V, double t) const = 0;
  /// Gradient over x, resized and overwritten.
  virtual void gradient(const Eigen::Ref<const MatrixX3d>& V, double t,
                        Eigen::VectorXd& gradient) const = 0;
  /// Hessian over x (both triangles stored); with `project_psd`, each element's block is
  /// projected to positive semi-definite, so the sum is too. The reference stays valid
  /// until the next call.
  virtual const Eigen::SparseMatrix<double>& hessian(const Eigen::Ref<const MatrixX3d>& V, double t,
                                                     bool project_psd) const = 0;
  /// Whether the Hessian's sparsity pattern is the same at every point (contact's follows
  /// the pairs in reach, so it is not).
  virtual bool fixed_pattern() const { return true; }
};

}  // namespace gr
