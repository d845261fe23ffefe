#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/common/types.hpp"

namespace gr {

/// How much a garment's shape changed from its input to its output (same vertices in the
/// same order, same faces). Ratios have no unit; both meshes must be in one unit.
struct ShapeChange {
  /// Median over edges of output length / input length: the garment's change of size.
  double scale = 1.0;
  /// Mean and 95th percentile over edges of |length_out / (scale * length_in) - 1|: how
  /// much edges stretched or shrank beyond the overall change of size.
  double mean_edge_change = 0.0;
  double p95_edge_change = 0.0;
  /// Largest |length_out / length_in - 1| over edges, not scale-free.
  double max_edge_change = 0.0;
  /// Total output area / total input area - 1 (negative when the garment shrank).
  double area_change = 0.0;
  /// Per boundary loop: mean displacement of its vertices over the input garment's
  /// bounding-box diagonal; the largest of them (0 for a garment without boundary).
  double loop_displacement = 0.0;
  std::vector<double> loop_displacements;  ///< per loop, in boundary_loops' order
  std::size_t edges = 0;                   ///< edges measured (input length > 0)
};

/// Measures `output` against `input`. Rows at identical input coordinates (OBJ seam
/// copies) are taken as one vertex, at the first row's output position, so that seams are
/// neither counted twice nor taken for boundary loops. Edges of zero input length are
/// left out; faces whose corners coincide give no boundary.
/// @param input #V×3 positions and #F×3 faces; output #V×3 positions of the same vertices.
/// @throw std::invalid_argument when the row counts differ, a face index is out of range or
///        no edge has a positive input length.
ShapeChange measure_shape_change(const TriangleMesh& input,
                                 const Eigen::Ref<const MatrixX3d>& output);

/// Limits on ShapeChange beyond which a garment counts as destroyed. Infinite limits (and
/// a scale range of [0, inf]) switch a check off.
struct ShapeThresholds {
  double min_scale = 0.8;
  double max_scale = 1.25;
  double mean_edge_change = 0.25;
  double p95_edge_change = 0.6;
  double area_change = 0.5;         ///< on |area_change|
  double loop_displacement = 0.25;  ///< of the input's bounding-box diagonal
  /// False switches every check off (the numbers are still measured and reported).
  bool enabled = true;
};

/// One line per exceeded threshold, naming the number, its value and its limit; empty when
/// the shape is within every limit or the check is switched off.
std::vector<std::string> shape_violations(const ShapeChange& change,
                                          const ShapeThresholds& thresholds);

/// The measurement, the thresholds and their violations as a JSON object:
/// `{scale, mean_edge_change, p95_edge_change, max_edge_change, area_change,
///   loop_displacement, loop_displacements, edges, thresholds {...}, violations [...],
///   within_thresholds}`. Infinite thresholds are written as null.
nlohmann::ordered_json shape_report(const ShapeChange& change, const ShapeThresholds& thresholds);

}  // namespace gr
