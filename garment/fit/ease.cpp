#include "garment/fit/ease.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

#include "core/common/errors.hpp"
#include "core/fit/garment_fit.hpp"
#include "core/mesh/boundary_loops.hpp"
#include "core/mesh/unique_edges.hpp"
#include "core/mesh/vertex_neighbours.hpp"
#include "shrink/level_set/triangle_tree.hpp"

namespace gr {

namespace {

double median_of(std::vector<double> values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace

const char* to_string(FitMode mode) { return mode == FitMode::kEase ? "ease" : "tight"; }

FitMode parse_fit_mode(const std::string& name) {
  if (name == "ease") return FitMode::kEase;
  if (name == "tight") return FitMode::kTight;
  throw InputError("", 0, "unknown fit mode '" + name + "' (ease or tight)");
}

SourceEase measure_source_ease(const TriangleMesh& garment, const TriangleMesh& body) {
  if (body.faces.rows() == 0) throw std::invalid_argument("source body has no face");
  const TriangleTree tree(body);
  const std::vector<bool> open = faces_on_open_edges(body.faces);
  const auto n = static_cast<std::size_t>(garment.vertices.rows());
  SourceEase ease;
  ease.distance.assign(n, 0.0);
  std::vector<bool> known(n, true);
  for (std::size_t v = 0; v < n; ++v) {
    int face = -1;
    const Vector3d p = garment.vertices.row(static_cast<Eigen::Index>(v)).transpose();
    ease.distance[v] = std::sqrt(tree.distance_sq(p, &face));
    if (face >= 0 && open[static_cast<std::size_t>(face)]) known[v] = false;
  }
  // Over a cut, the ease spreads in from the neighbours, one ring per sweep (each sweep
  // reads the last one's values, so the order of the vertices does not matter).
  const auto neighbours = vertex_neighbours(garment);
  for (bool changed = true; changed;) {
    changed = false;
    std::vector<bool> next = known;
    std::vector<double> value = ease.distance;
    for (std::size_t v = 0; v < n; ++v) {
      if (known[v]) continue;
      double sum = 0.0;
      int count = 0;
      for (const int u : neighbours[v])
        if (known[static_cast<std::size_t>(u)]) {
          sum += ease.distance[static_cast<std::size_t>(u)];
          ++count;
        }
      if (count == 0) continue;
      value[v] = sum / count;
      next[v] = true;
      ++ease.filled;
      changed = true;
    }
    known = std::move(next);
    ease.distance = std::move(value);
  }
  for (std::size_t v = 0; v < n; ++v)
    if (!known[v]) {
      ease.distance[v] = 0.0;  // a piece with no vertex over the body: tight
      ++ease.filled;
    }
  return ease;
}

EaseTargets ease_targets(const TriangleMesh& rest, const Eigen::Ref<const MatrixX3d>& inflated,
                         const SourceEase& source, double max_offset) {
  const auto n = static_cast<std::size_t>(rest.vertices.rows());
  if (source.distance.size() != n)
    throw std::invalid_argument("source ease and garment differ in vertex count");
  const double global = median_edge_ratio(rest, inflated);
  std::vector<std::vector<double>> stretch(n);
  const MatrixX2i edges = unique_edges(rest.faces);
  for (Eigen::Index e = 0; e < edges.rows(); ++e) {
    const int a = edges(e, 0), b = edges(e, 1);
    const double length = (rest.vertices.row(a) - rest.vertices.row(b)).norm();
    if (!(length > 0.0)) continue;
    const double ratio = (inflated.row(a) - inflated.row(b)).norm() / length;
    stretch[static_cast<std::size_t>(a)].push_back(ratio);
    stretch[static_cast<std::size_t>(b)].push_back(ratio);
  }
  std::vector<double> scale(n, global);
  for (std::size_t v = 0; v < n; ++v)
    if (!stretch[v].empty()) scale[v] = median_of(stretch[v]);
  const auto neighbours = vertex_neighbours(rest);
  constexpr int kSmoothingRings = 2;
  for (int ring = 0; ring < kSmoothingRings; ++ring) {
    std::vector<double> smoothed(n);
    for (std::size_t v = 0; v < n; ++v) {
      double sum = scale[v];
      for (const int u : neighbours[v]) sum += scale[static_cast<std::size_t>(u)];
      smoothed[v] = sum / static_cast<double>(neighbours[v].size() + 1);
    }
    scale = std::move(smoothed);
  }
  EaseTargets targets;
  targets.offsets.resize(n);
  for (std::size_t v = 0; v < n; ++v) {
    scale[v] = std::clamp(scale[v], 0.5 * global, 2.0 * global);
    const double offset = source.distance[v] * scale[v];
    targets.capped += offset > max_offset;
    targets.offsets[v] = std::min(offset, max_offset);
  }
  if (n > 0) {
    targets.min_scale = *std::min_element(scale.begin(), scale.end());
    targets.max_scale = *std::max_element(scale.begin(), scale.end());
    targets.median_scale = median_of(scale);
  }
  return targets;
}

EaseMeasure measure_ease(const TriangleMesh& rest, const Eigen::Ref<const MatrixX3d>& written,
                         const TriangleMesh& avatar, const SourceEase& source,
                         const std::vector<bool>& fit_faces, double min_ease) {
  const auto n = static_cast<std::size_t>(rest.vertices.rows());
  EaseMeasure measure;
  measure.ratio.assign(n, std::numeric_limits<double>::quiet_NaN());
  measure.scale = median_edge_ratio(rest, written);
  std::vector<bool> fitted(n, false);
  for (Eigen::Index f = 0; f < rest.faces.rows(); ++f)
    if (fit_faces[static_cast<std::size_t>(f)])
      for (int k = 0; k < 3; ++k) fitted[static_cast<std::size_t>(rest.faces(f, k))] = true;
  const TriangleTree tree(avatar);
  std::vector<double> ratios;
  double error = 0.0;
  int within = 0;
  for (std::size_t v = 0; v < n; ++v) {
    if (!fitted[v] || !(source.distance[v] >= min_ease)) continue;
    const Vector3d p = written.row(static_cast<Eigen::Index>(v)).transpose();
    const double out = std::sqrt(tree.distance_sq(p));
    const double ratio = out / (measure.scale * source.distance[v]);
    measure.ratio[v] = ratio;
    ratios.push_back(ratio);
    error += std::abs(ratio - 1.0);
    within += std::abs(ratio - 1.0) <= 0.25;
  }
  measure.vertices = static_cast<int>(ratios.size());
  if (!ratios.empty()) {
    measure.median_ratio = median_of(ratios);
    measure.mean_error = error / static_cast<double>(ratios.size());
    measure.within_25_percent = static_cast<double>(within) / static_cast<double>(ratios.size());
  }
  return measure;
}

}  // namespace gr
