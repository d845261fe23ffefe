#pragma once

#include <Eigen/SparseCore>

namespace gr {

/// Walks the entries of A (compressed, column-major) against the sparsity pattern of
/// `pattern` (compressed, same size): for each entry a_rc calls `inside(k, value)` with k
/// its index in pattern's value array when the pattern holds (r, c), else
/// `outside(r, c, value)`, which returns false to stop the walk.
/// @return false when `outside` stopped it.
template <typename Inside, typename Outside>
bool for_each_entry_in_pattern(const Eigen::SparseMatrix<double>& A,
                               const Eigen::SparseMatrix<double>& pattern, Inside inside,
                               Outside outside) {
  const int* outer = pattern.outerIndexPtr();
  const int* inner = pattern.innerIndexPtr();
  for (Eigen::Index c = 0; c < A.outerSize(); ++c) {
    int k = outer[c];
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, c); it; ++it) {
      while (k < outer[c + 1] && inner[k] < it.index()) ++k;
      if (k < outer[c + 1] && inner[k] == it.index())
        inside(k, it.value());
      else if (!outside(it.index(), c, it.value()))
        return false;
    }
  }
  return true;
}

/// target += weight · A. @pre A's pattern lies within target's (both compressed, same size).
inline void add_within_pattern(const Eigen::SparseMatrix<double>& A, double weight,
                               Eigen::SparseMatrix<double>& target) {
  double* values = target.valuePtr();
  const bool within = for_each_entry_in_pattern(
      A, target, [&](int k, double value) { values[k] += weight * value; },
      [](Eigen::Index, Eigen::Index, double) { return false; });
  eigen_assert(within);
  (void)within;
}

}  // namespace gr
