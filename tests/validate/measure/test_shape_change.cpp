#include <cmath>
#include <limits>
#include <stdexcept>

#include <catch2/catch.hpp>

#include "validate/measure/shape_change.hpp"

using gr::MatrixX3d;
using gr::ShapeChange;
using gr::ShapeThresholds;
using gr::TriangleMesh;

namespace {

/// A flat n×n grid of unit-square cells in z = 0, each cell split along one diagonal.
/// With `seam`, the middle column of vertices is written twice (the left half's faces use
/// one copy, the right half's the other), as an OBJ does along a UV seam.
TriangleMesh grid_patch(int n, bool seam = false) {
  const int columns = n + 1 + (seam ? 1 : 0);
  const int middle = n / 2;
  TriangleMesh mesh;
  mesh.vertices.resize(columns * (n + 1), 3);
  const auto id = [&](int i, int j, bool right) {
    const int column = seam && (i > middle || (i == middle && right)) ? i + 1 : i;
    return j * columns + column;
  };
  for (int j = 0; j <= n; ++j)
    for (int c = 0; c < columns; ++c) {
      const int x = seam && c > middle ? c - 1 : c;
      mesh.vertices.row(j * columns + c) << x, j, 0.0;
    }
  mesh.faces.resize(2 * n * n, 3);
  int f = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const bool right = i >= middle;
      mesh.faces.row(f++) << id(i, j, right), id(i + 1, j, right), id(i + 1, j + 1, right);
      mesh.faces.row(f++) << id(i, j, right), id(i + 1, j + 1, right), id(i, j + 1, right);
    }
  return mesh;
}

}  // namespace

TEST_CASE("shape change: the unchanged garment has scale 1 and no change", "[validate][shape]") {
  const bool seam = GENERATE(false, true);
  CAPTURE(seam);
  const TriangleMesh patch = grid_patch(6, seam);
  const ShapeChange change = gr::measure_shape_change(patch, patch.vertices);
  CHECK(change.scale == 1.0);
  CHECK(change.mean_edge_change == 0.0);
  CHECK(change.p95_edge_change == 0.0);
  CHECK(change.max_edge_change == 0.0);
  CHECK(change.area_change == 0.0);
  CHECK(change.loop_displacement == 0.0);
  // Seam copies are one vertex: one boundary loop and the edges of the welded grid.
  CHECK(change.loop_displacements.size() == 1);
  CHECK(change.edges == static_cast<std::size_t>(2 * 6 * 7 + 6 * 6));
  CHECK(gr::shape_violations(change, ShapeThresholds{}).empty());
}

TEST_CASE("shape change: a uniform scale is the scale and no scale-free change",
          "[validate][shape]") {
  const TriangleMesh patch = grid_patch(5);
  const double factor = GENERATE(1.1, 0.3, 2.0);
  CAPTURE(factor);
  const MatrixX3d scaled = factor * patch.vertices;
  const ShapeChange change = gr::measure_shape_change(patch, scaled);
  CHECK(change.scale == Approx(factor).epsilon(1e-12));
  CHECK(change.mean_edge_change == Approx(0.0).margin(1e-12));
  CHECK(change.p95_edge_change == Approx(0.0).margin(1e-12));
  CHECK(change.max_edge_change == Approx(std::abs(factor - 1.0)).epsilon(1e-12));
  CHECK(change.area_change == Approx(factor * factor - 1.0).epsilon(1e-12));
  const ShapeThresholds limits;
  const bool size_kept = factor >= limits.min_scale && factor <= limits.max_scale;
  CHECK(gr::shape_violations(change, limits).empty() == size_kept);
}

TEST_CASE("shape change: a patch stretched along x", "[validate][shape]") {
  const int n = 8;
  const TriangleMesh patch = grid_patch(n);
  const double stretch = 1.5;
  MatrixX3d stretched = patch.vertices;
  stretched.col(0) *= stretch;
  const ShapeChange change = gr::measure_shape_change(patch, stretched);

  // Edges: n(n+1) along y (ratio 1), n(n+1) along x (ratio 1.5), n² diagonals. The
  // diagonals hold the middle rank, so the median is their ratio.
  const double rows = n * (n + 1), diagonals = n * n;
  const double diagonal_ratio = std::sqrt((stretch * stretch + 1.0) / 2.0);
  const double y_change = std::abs(1.0 / diagonal_ratio - 1.0);
  const double x_change = std::abs(stretch / diagonal_ratio - 1.0);
  CHECK(change.scale == Approx(diagonal_ratio).epsilon(1e-12));
  CHECK(change.mean_edge_change ==
        Approx(rows * (y_change + x_change) / (2.0 * rows + diagonals)).epsilon(1e-12));
  CHECK(change.p95_edge_change == Approx(std::max(y_change, x_change)).epsilon(1e-12));
  CHECK(change.max_edge_change == Approx(stretch - 1.0).epsilon(1e-12));
  CHECK(change.area_change == Approx(stretch - 1.0).epsilon(1e-12));
  // The boundary's mean displacement: (|x| (stretch - 1)) averaged over the boundary ring.
  double moved = 0.0;
  int count = 0;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      if (i != 0 && i != n && j != 0 && j != n) continue;
      moved += i * (stretch - 1.0);
      ++count;
    }
  CHECK(change.loop_displacement == Approx(moved / count / (n * std::sqrt(2.0))).epsilon(1e-12));
}

TEST_CASE("shape change: a moved garment keeps its shape but its loops move", "[validate][shape]") {
  const TriangleMesh patch = grid_patch(4);
  MatrixX3d moved = patch.vertices;
  moved.rowwise() += gr::RowVector3d(0.0, 0.0, 3.0);
  const ShapeChange change = gr::measure_shape_change(patch, moved);
  CHECK(change.scale == Approx(1.0).epsilon(1e-12));
  CHECK(change.mean_edge_change == Approx(0.0).margin(1e-12));
  CHECK(change.area_change == Approx(0.0).margin(1e-12));
  // Diagonal of the 4×4 patch: 4 sqrt(2).
  CHECK(change.loop_displacement == Approx(3.0 / (4.0 * std::sqrt(2.0))).epsilon(1e-12));
  const auto violations = gr::shape_violations(change, ShapeThresholds{});
  REQUIRE(violations.size() == 1);
  CHECK(violations.front().find("boundary loop") != std::string::npos);

  ShapeThresholds off;
  off.enabled = false;
  CHECK(gr::shape_violations(change, off).empty());
  ShapeThresholds infinite;
  infinite.loop_displacement = std::numeric_limits<double>::infinity();
  CHECK(gr::shape_violations(change, infinite).empty());
  const auto report = gr::shape_report(change, infinite);
  CHECK(report["thresholds"]["loop_displacement"].is_null());
  CHECK(report["within_thresholds"] == true);
}

TEST_CASE("shape change: a crushed garment exceeds every limit", "[validate][shape]") {
  const TriangleMesh patch = grid_patch(6);
  MatrixX3d crushed = 0.3 * patch.vertices;
  for (Eigen::Index v = 0; v < crushed.rows(); ++v) crushed(v, 0) *= v % 2 == 0 ? 0.1 : 1.0;
  const ShapeChange change = gr::measure_shape_change(patch, crushed);
  CHECK(change.scale < 0.8);
  CHECK(change.mean_edge_change > 0.25);
  CHECK(change.area_change < -0.5);
  CHECK(gr::shape_violations(change, ShapeThresholds{}).size() >= 3);
}

TEST_CASE("shape change: mismatched or empty inputs are refused", "[validate][shape]") {
  const TriangleMesh patch = grid_patch(2);
  const MatrixX3d fewer = patch.vertices.topRows(patch.vertices.rows() - 1);
  CHECK_THROWS_AS(gr::measure_shape_change(patch, fewer), std::invalid_argument);
  TriangleMesh collapsed = patch;
  collapsed.vertices.setZero();
  CHECK_THROWS_AS(gr::measure_shape_change(collapsed, collapsed.vertices), std::invalid_argument);
}
