#pragma once

#include <Eigen/SparseCore>

#include "core/candidates/candidates.hpp"
#include "core/ccd/ccd.hpp"
#include "core/energies/dof_layout.hpp"
#include "core/energies/energy_term.hpp"
#include "core/potentials/barrier_potential.hpp"

namespace gr {

/// L_contact (unweighted) on the solver's unknowns: the IPC barrier over the stacked
/// vertices V = [Vg; A(t)] with the avatar moving as A(t) = A0 + t (A - A0). Derivatives
/// are chained to x through J = dV/dx, the identity on garment coordinates and the column
/// vec(A - A0) for t (when the layout frees t): grad_x = Jᵀ grad_V, H_x = Jᵀ H_V J (PSD when
/// H_V is). Keeps the current candidate set: pairs within dhat of the current point, or
/// after `update_swept_candidates`, pairs that come within dhat anywhere along a motion.
/// Not safe for concurrent use (it keeps the candidates and a stacked-vertex buffer).
/// Not a StencilTerm: its pairs, and so its Hessian's pattern, change with every candidate
/// update, and its stencils are on the stacked vertices (avatar included), summed by
/// BarrierPotential and chained to x through J, not on x directly.
class ContactEnergy : public EnergyTerm {
 public:
  /// @param mesh garment and avatar stacked (the avatar's rows in A's order).
  /// @param garment_rest rest garment (#Vg×3), with `avatar_end` the barrier's rest shape
  ///        for the edge–edge mollifier.
  /// @param avatar_start A0 (#Va×3), the avatar at t = 0.
  /// @param avatar_end A (#Va×3), the avatar at t = 1.
  /// @param dhat barrier support, normalized scene units.
  ContactEnergy(ContactMesh mesh, const Eigen::Ref<const MatrixX3d>& garment_rest,
                const Eigen::Ref<const MatrixX3d>& avatar_start,
                const Eigen::Ref<const MatrixX3d>& avatar_end, double dhat,
                const DofLayout& layout);

  const ContactMesh& mesh() const { return finder_.mesh(); }
  const Candidates& candidates() const { return candidates_; }
  double dhat() const { return barrier_.dhat(); }
  /// Mean fraction of garment faces whose self pairs were left out as fold free, over the
  /// swept searches so far (CandidateFinder::mean_fold_free_fraction).
  double mean_fold_free_fraction() const { return finder_.mean_fold_free_fraction(); }

  /// The avatar at t (#Va×3).
  MatrixX3d avatar(double t) const { return avatar_start_ + t * displacement_; }
  /// [Vg; A(t)] (#V×3) for garment positions V (#Vg×3).
  const MatrixX3d& stacked(const Eigen::Ref<const MatrixX3d>& V, double t) const;
  /// Largest avatar vertex displacement |A_i - A0_i| (normalized units): the length by
  /// which a unit change of t moves the avatar at most.
  double max_displacement() const { return max_displacement_; }

  /// Candidates at (V, t): every pair closer than dhat.
  void update_candidates(const Eigen::Ref<const MatrixX3d>& V, double t);
  /// Candidates along the linear motion (V0, t0) → (V1, t1), replacing the current ones,
  /// and the CCD bound: the largest fraction of the motion that is collision free.
  double update_swept_candidates(const Eigen::Ref<const MatrixX3d>& V0, double t0,
                                 const Eigen::Ref<const MatrixX3d>& V1, double t1,
                                 const CcdOptions& ccd);
  /// As update_swept_candidates, but per garment vertex (ccd.hpp, vertex_steps): the
  /// smallest CCD bound over the pairs it belongs to (garment–garment pairs only with
  /// `self_only`), 1 where none cuts its motion.
  std::vector<double> update_swept_vertex_steps(const Eigen::Ref<const MatrixX3d>& V0, double t0,
                                                const Eigen::Ref<const MatrixX3d>& V1, double t1,
                                                const CcdOptions& ccd, bool self_only = false);

  const char* name() const override { return "contact"; }
  /// Over the current candidates.
  double value(const Eigen::Ref<const MatrixX3d>& V, double t) const override;
  void gradient(const Eigen::Ref<const MatrixX3d>& V, double t,
                Eigen::VectorXd& gradient) const override;
  /// Pair blocks projected to PSD when `project_psd`; the pattern follows the candidates.
  const Eigen::SparseMatrix<double>& hessian(const Eigen::Ref<const MatrixX3d>& V, double t,
                                             bool project_psd) const override;
  bool fixed_pattern() const override { return false; }
  /// Smallest distance over the current candidates (+inf when there are none).
  double minimum_distance(const Eigen::Ref<const MatrixX3d>& V, double t) const;

 private:
  CandidateFinder finder_;
  BarrierPotential barrier_;
  DofLayout layout_;
  MatrixX3d avatar_start_, displacement_;
  double max_displacement_ = 0.0;
  Eigen::SparseMatrix<double> jacobian_, jacobian_transpose_;  ///< dV/dx, 3#V × #dofs
  Candidates candidates_;
  mutable MatrixX3d stacked_;
  mutable Eigen::SparseMatrix<double> hessian_;  ///< the last hessian() result
};

}  // namespace gr
