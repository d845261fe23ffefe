#pragma once

#include <Eigen/SparseCore>

#include "core/candidates/candidates.hpp"
#include "core/distance/stencil.hpp"

namespace gr {

/// IPC barrier summed over a candidate set: sum of b(d^2, dhat^2) with
/// b(x, xhat) = -(x - xhat)^2 ln(x / xhat) for 0 < x < xhat, 0 beyond, on squared
/// distances; edge–edge pairs are multiplied by IPC's mollifier near parallel edges.
/// Unweighted: the caller multiplies by w_contact.
class BarrierPotential {
 public:
  /// @param dhat barrier support as a distance (not squared), normalized scene units.
  /// @param rest_vertices stacked rest positions (#V×3), for the edge–edge mollifier's
  ///        threshold (1e-3 times the product of the rest squared edge lengths); an
  ///        edge–edge pair with a zero-length rest edge contributes nothing.
  /// @throw InputError when dhat is not positive and finite.
  BarrierPotential(double dhat, const Eigen::Ref<const MatrixX3d>& rest_vertices);

  double dhat() const { return dhat_; }

  /// Sum over candidates at V (#V×3). +inf when a pair is at zero distance.
  double value(const Candidates& candidates, const Eigen::Ref<const MatrixX3d>& V) const;
  /// Gradient, 3#V, vertex-major (x0 y0 z0 x1 ...). Pairs at zero distance (where the
  /// value is +inf) contribute nothing. Sums are in candidate order on any thread count.
  Eigen::VectorXd gradient(const Candidates& candidates,
                           const Eigen::Ref<const MatrixX3d>& V) const;
  /// Hessian, 3#V×3#V, compressed column storage; each pair's 12×12 block projected to PSD
  /// (core/common/psd_projection.hpp) when `project_psd`.
  Eigen::SparseMatrix<double> hessian(const Candidates& candidates,
                                      const Eigen::Ref<const MatrixX3d>& V,
                                      bool project_psd = true) const;
  /// Smallest distance (not squared) over the candidates; +inf when there are none.
  double minimum_distance(const Candidates& candidates, const Eigen::Ref<const MatrixX3d>& V) const;

 private:
  /// One pair's energy; `active` when 0 < d² < dhat² (the pair then has derivatives).
  struct PairEnergy {
    double value;
    bool active;
  };
  /// Candidate k of the stacked list (point–triangle first, then edge–edge): its energy
  /// and, when active and asked, its gradient and Hessian on the 12-stencil.
  PairEnergy pair_energy(const Candidates& candidates, std::size_t k,
                         const Eigen::Ref<const MatrixX3d>& V, Vector12d* gradient,
                         Matrix12d* hessian) const;

  double dhat_;
  MatrixX3d rest_vertices_;
};

}  // namespace gr
