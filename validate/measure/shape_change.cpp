#include "validate/measure/shape_change.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "core/mesh/boundary_loops.hpp"
#include "core/mesh/unique_edges.hpp"
#include "validate/checks/position_identity.hpp"

namespace gr {

namespace {

/// The q-quantile of `values` by rank ceil(q n) - 1 (reorders `values`).
/// @pre values is not empty.
double quantile(std::vector<double>& values, double q) {
  const auto n = static_cast<double>(values.size());
  const auto rank = static_cast<std::ptrdiff_t>(std::max(std::ceil(q * n) - 1.0, 0.0));
  std::nth_element(values.begin(), values.begin() + rank, values.end());
  return values[static_cast<std::size_t>(rank)];
}

/// Median with the mean of the two middle values for an even count (reorders `values`).
double median(std::vector<double>& values) {
  const std::size_t half = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(half),
                   values.end());
  const double upper = values[half];
  if (values.size() % 2 == 1) return upper;
  const double lower =
      *std::max_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(half));
  return 0.5 * (lower + upper);
}

double total_area(const Eigen::Ref<const MatrixX3d>& vertices, const MatrixX3i& faces) {
  double area = 0.0;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const RowVector3d a = vertices.row(faces(f, 0));
    const RowVector3d b = vertices.row(faces(f, 1));
    const RowVector3d c = vertices.row(faces(f, 2));
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  return area;
}

/// Faces on the first row of each group of identical input positions, without the faces
/// whose corners then coincide.
MatrixX3i welded_faces(const TriangleMesh& input) {
  const std::vector<int> same = position_identity(input.vertices);
  MatrixX3i faces(input.faces.rows(), 3);
  Eigen::Index kept = 0;
  for (Eigen::Index f = 0; f < input.faces.rows(); ++f) {
    int corner[3];
    for (int k = 0; k < 3; ++k) {
      const int v = input.faces(f, k);
      if (v < 0 || v >= input.vertices.rows())
        throw std::invalid_argument(fmt::format("shape change: face {} names vertex {} of {}", f, v,
                                                input.vertices.rows()));
      corner[k] = same[static_cast<std::size_t>(v)];
    }
    if (corner[0] == corner[1] || corner[1] == corner[2] || corner[0] == corner[2]) continue;
    faces.row(kept++) << corner[0], corner[1], corner[2];
  }
  faces.conservativeResize(kept, 3);
  return faces;
}

}  // namespace

ShapeChange measure_shape_change(const TriangleMesh& input,
                                 const Eigen::Ref<const MatrixX3d>& output) {
  if (output.rows() != input.vertices.rows())
    throw std::invalid_argument(fmt::format("shape change: output has {} vertices, input {}",
                                            output.rows(), input.vertices.rows()));
  const MatrixX3i faces = welded_faces(input);
  const MatrixX2i edges = unique_edges(faces);

  std::vector<double> ratios;
  ratios.reserve(static_cast<std::size_t>(edges.rows()));
  for (Eigen::Index e = 0; e < edges.rows(); ++e) {
    const double length_in =
        (input.vertices.row(edges(e, 0)) - input.vertices.row(edges(e, 1))).norm();
    if (!(length_in > 0.0)) continue;
    ratios.push_back((output.row(edges(e, 0)) - output.row(edges(e, 1))).norm() / length_in);
  }
  if (ratios.empty())
    throw std::invalid_argument("shape change: the input has no edge of positive length");

  ShapeChange change;
  change.edges = ratios.size();
  std::vector<double> changes(ratios.size());
  for (std::size_t e = 0; e < ratios.size(); ++e)
    change.max_edge_change = std::max(change.max_edge_change, std::abs(ratios[e] - 1.0));
  change.scale = median(ratios);  // reorders ratios: the changes below need no order
  for (std::size_t e = 0; e < ratios.size(); ++e)
    changes[e] = std::abs(ratios[e] / change.scale - 1.0);
  double sum = 0.0;
  for (const double c : changes) sum += c;
  change.mean_edge_change = sum / static_cast<double>(changes.size());
  change.p95_edge_change = quantile(changes, 0.95);

  const double area_in = total_area(input.vertices, faces);
  change.area_change = area_in > 0.0 ? total_area(output, faces) / area_in - 1.0 : 0.0;

  const double diagonal =
      (input.vertices.colwise().maxCoeff() - input.vertices.colwise().minCoeff()).norm();
  for (const std::vector<int>& loop : boundary_loops(faces)) {
    double moved = 0.0;
    for (const int v : loop) moved += (output.row(v) - input.vertices.row(v)).norm();
    const double displacement = moved / static_cast<double>(loop.size()) / diagonal;
    change.loop_displacements.push_back(displacement);
    change.loop_displacement = std::max(change.loop_displacement, displacement);
  }
  return change;
}

std::vector<std::string> shape_violations(const ShapeChange& change,
                                          const ShapeThresholds& limits) {
  std::vector<std::string> out;
  if (!limits.enabled) return out;
  if (change.scale < limits.min_scale || change.scale > limits.max_scale)
    out.push_back(fmt::format("scale (median edge-length ratio) {:.3g} is outside [{:.3g}, {:.3g}]",
                              change.scale, limits.min_scale, limits.max_scale));
  if (change.mean_edge_change > limits.mean_edge_change)
    out.push_back(fmt::format("scale-free mean edge-length change {:.3g} is above {:.3g}",
                              change.mean_edge_change, limits.mean_edge_change));
  if (change.p95_edge_change > limits.p95_edge_change)
    out.push_back(
        fmt::format("scale-free 95th-percentile edge-length change {:.3g} is above {:.3g}",
                    change.p95_edge_change, limits.p95_edge_change));
  if (std::abs(change.area_change) > limits.area_change)
    out.push_back(fmt::format("area changed by {:+.3g} (relative), beyond {:.3g}",
                              change.area_change, limits.area_change));
  if (change.loop_displacement > limits.loop_displacement)
    out.push_back(fmt::format(
        "a boundary loop moved {:.3g} of the garment's bounding-box diagonal, beyond {:.3g}",
        change.loop_displacement, limits.loop_displacement));
  return out;
}

nlohmann::ordered_json shape_report(const ShapeChange& change, const ShapeThresholds& limits) {
  const auto limit = [](double value) {
    return std::isfinite(value) ? nlohmann::ordered_json(value) : nlohmann::ordered_json(nullptr);
  };
  const std::vector<std::string> violations = shape_violations(change, limits);
  return {
      {"scale", change.scale},
      {"mean_edge_change", change.mean_edge_change},
      {"p95_edge_change", change.p95_edge_change},
      {"max_edge_change", change.max_edge_change},
      {"area_change", change.area_change},
      {"loop_displacement", change.loop_displacement},
      {"loop_displacements", change.loop_displacements},
      {"edges", change.edges},
      {"thresholds",
       {{"enabled", limits.enabled},
        {"min_scale", limit(limits.min_scale)},
        {"max_scale", limit(limits.max_scale)},
        {"mean_edge_change", limit(limits.mean_edge_change)},
        {"p95_edge_change", limit(limits.p95_edge_change)},
        {"area_change", limit(limits.area_change)},
        {"loop_displacement", limit(limits.loop_displacement)}}},
      {"violations", violations},
      {"within_thresholds", violations.empty()},
      {"meaning",
       "scale: median over edges of output/input length; edge changes: |out/(scale in) - 1| "
       "over edges; area_change: output/input total area - 1; loop_displacement: largest over "
       "boundary loops of the mean vertex displacement over the input's bounding-box diagonal"},
  };
}

}  // namespace gr
