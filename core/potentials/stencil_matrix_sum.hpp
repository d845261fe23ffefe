#pragma once

#include <array>
#include <vector>

#include <Eigen/SparseCore>

#include "core/distance/stencil.hpp"

namespace gr {

/// A 4-vertex stencil's 12×12 matrix and the vertices it acts on.
struct StencilMatrix {
  std::array<int, 4> vertices;
  Matrix12d matrix;
};

/// Sum of stencil matrices into a sparse 3n×3n matrix (vertex-major: rows 3i..3i+2 are
/// vertex i). Works on 3×3 vertex blocks, column vertices in parallel; the result is the
/// same on any thread count. The pattern is made anew from each call's stencils (contact
/// pairs change between calls); a term over a fixed element list keeps its pattern with
/// StencilAssembly (core/energies/stencil_assembly.hpp) instead.
/// @pre every vertex index in [0, vertex_count).
Eigen::SparseMatrix<double> assemble_stencil_matrices(int vertex_count,
                                                      const std::vector<StencilMatrix>& stencils);

}  // namespace gr
