#pragma once

#include <Eigen/Core>

#include "core/common/types.hpp"

namespace gr {

/// Where the unknowns sit in the solver's vector x. With a free avatar parameter
/// (inflation) x = [t, x0, y0, z0, x1, ...] over the garment vertices; with t fixed (fit)
/// x = [x0, y0, z0, x1, ...] and t takes `fixed_t`.
struct DofLayout {
  int garment_vertex_count = 0;
  bool t_free = false;
  double fixed_t = 1.0;  ///< the avatar parameter when t is not an unknown

  int dof_count() const { return 3 * garment_vertex_count + (t_free ? 1 : 0); }
  /// Index of t in x, or -1 when t is fixed.
  int t_index() const { return t_free ? 0 : -1; }
  int position_offset() const { return t_free ? 1 : 0; }
  /// Index of coordinate `axis` (0..2) of garment vertex `vertex` in x.
  int vertex_dof(int vertex, int axis) const { return position_offset() + 3 * vertex + axis; }

  double t(const Eigen::VectorXd& x) const { return t_free ? x[0] : fixed_t; }
  /// The garment vertices (#Vg×3) of x, as a view into x (so x must outlive it).
  Eigen::Map<const MatrixX3d> garment(const Eigen::VectorXd& x) const {
    return Eigen::Map<const MatrixX3d>(x.data() + position_offset(), garment_vertex_count, 3);
  }
  Eigen::Map<const MatrixX3d> garment(Eigen::VectorXd&& temporary) const = delete;
  /// x from t and the garment vertices (#Vg×3).
  Eigen::VectorXd pack(double t, const Eigen::Ref<const MatrixX3d>& garment) const {
    Eigen::VectorXd x(dof_count());
    if (t_free) x[0] = t;
    Eigen::Map<MatrixX3d>(x.data() + position_offset(), garment_vertex_count, 3) = garment;
    return x;
  }
};

}  // namespace gr
