#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace gr {

using Vector3d = Eigen::Vector3d;
using Vector2d = Eigen::Vector2d;
using RowVector3d = Eigen::RowVector3d;
using VectorXd = Eigen::VectorXd;
using VectorXi = Eigen::VectorXi;
/// Vertex positions, one row per vertex (#V×3).
using MatrixX3d = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
/// Triangle vertex indices, one row per face (#F×3).
using MatrixX3i = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;
/// Edge vertex indices, one row per edge (#E×2).
using MatrixX2i = Eigen::Matrix<int, Eigen::Dynamic, 2, Eigen::RowMajor>;

/// A triangle mesh as plain arrays: positions and faces.
struct TriangleMesh {
  MatrixX3d vertices;  ///< #V×3
  MatrixX3i faces;     ///< #F×3, 0-based indices into vertices
};

}  // namespace gr
