#include "core/potentials/stencil_matrix_sum.hpp"

#include <algorithm>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace gr {
namespace {

/// One 3×3 block of one stencil: (row vertex, stencil, block row, block column).
struct BlockRef {
  int row_vertex;
  int stencil;
  int block_row;
  int block_col;
};

}  // namespace

Eigen::SparseMatrix<double> assemble_stencil_matrices(int vertex_count,
                                                      const std::vector<StencilMatrix>& stencils) {
  const auto n = static_cast<std::size_t>(vertex_count);
  // Bucket every block by its column vertex (counting sort keeps stencil order).
  std::vector<int> column_start(n + 1, 0);
  for (const StencilMatrix& s : stencils)
    for (int c = 0; c < 4; ++c) column_start[static_cast<std::size_t>(s.vertices[c]) + 1] += 4;
  for (std::size_t v = 0; v < n; ++v) column_start[v + 1] += column_start[v];
  std::vector<BlockRef> blocks(static_cast<std::size_t>(column_start[n]));
  std::vector<int> fill(column_start.begin(), column_start.end() - 1);
  for (std::size_t k = 0; k < stencils.size(); ++k)
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r)
        blocks[static_cast<std::size_t>(
            fill[static_cast<std::size_t>(stencils[k].vertices[c])]++)] =
            BlockRef{stencils[k].vertices[r], static_cast<int>(k), r, c};

  // Per column vertex: sort by row vertex and count distinct row vertices.
  std::vector<int> distinct_rows(n, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 256), [&](const auto& range) {
    for (std::size_t v = range.begin(); v != range.end(); ++v) {
      const auto first = blocks.begin() + column_start[v],
                 last = blocks.begin() + column_start[v + 1];
      std::stable_sort(first, last, [](const BlockRef& a, const BlockRef& b) {
        return a.row_vertex < b.row_vertex;
      });
      int count = 0;
      for (auto it = first; it != last; ++it)
        if (it == first || it->row_vertex != (it - 1)->row_vertex) ++count;
      distinct_rows[v] = count;
    }
  });

  Eigen::SparseMatrix<double> out(3 * vertex_count, 3 * vertex_count);
  std::vector<Eigen::Index> outer(3 * n + 1, 0);
  for (std::size_t v = 0; v < n; ++v)
    for (std::size_t d = 0; d < 3; ++d)
      outer[3 * v + d + 1] = outer[3 * v + d] + 3 * distinct_rows[v];
  out.resizeNonZeros(outer[3 * n]);
  std::copy(outer.begin(), outer.end(), out.outerIndexPtr());
  double* values = out.valuePtr();
  auto* inner = out.innerIndexPtr();

  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 256), [&](const auto& range) {
    for (std::size_t v = range.begin(); v != range.end(); ++v) {
      int slot = -1;  // index of the current distinct row block within this column vertex
      for (int b = column_start[v]; b < column_start[v + 1]; ++b) {
        const BlockRef& ref = blocks[static_cast<std::size_t>(b)];
        const bool fresh = b == column_start[v] ||
                           ref.row_vertex != blocks[static_cast<std::size_t>(b) - 1].row_vertex;
        if (fresh) ++slot;
        const Matrix12d& m = stencils[static_cast<std::size_t>(ref.stencil)].matrix;
        for (int d = 0; d < 3; ++d) {
          const Eigen::Index start = outer[3 * v + static_cast<std::size_t>(d)] + 3 * slot;
          for (int r = 0; r < 3; ++r) {
            if (fresh) {
              inner[start + r] = 3 * ref.row_vertex + r;
              values[start + r] = 0.0;
            }
            values[start + r] += m(3 * ref.block_row + r, 3 * ref.block_col + d);
          }
        }
      }
    }
  });
  return out;
}

}  // namespace gr
