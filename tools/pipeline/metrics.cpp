#include "tools/pipeline/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/mesh/unique_edges.hpp"
#include "validate/measure/surface_distance.hpp"

namespace gr {

FitError measure_fit_error(const TriangleMesh& garment, const std::vector<bool>& fit_faces,
                           const TriangleMesh& avatar) {
  std::vector<Vector3d> samples;
  for (Eigen::Index f = 0; f < garment.faces.rows(); ++f) {
    if (!fit_faces[static_cast<std::size_t>(f)]) continue;
    const Vector3d a = garment.vertices.row(garment.faces(f, 0)).transpose();
    const Vector3d b = garment.vertices.row(garment.faces(f, 1)).transpose();
    const Vector3d c = garment.vertices.row(garment.faces(f, 2)).transpose();
    const Vector3d centroid = (a + b + c) / 3.0;
    samples.push_back(centroid);
    for (const Vector3d& corner : {a, b, c}) samples.push_back(0.5 * (centroid + corner));
  }
  FitError error;
  error.samples = samples.size();
  if (samples.empty()) return error;
  MatrixX3d points(static_cast<Eigen::Index>(samples.size()), 3);
  for (std::size_t i = 0; i < samples.size(); ++i)
    points.row(static_cast<Eigen::Index>(i)) = samples[i].transpose();
  std::vector<double> d = distances_to_surface(avatar, points);
  error.mean = std::accumulate(d.begin(), d.end(), 0.0) / static_cast<double>(d.size());
  const auto rank = static_cast<std::size_t>(std::ceil(0.95 * static_cast<double>(d.size()))) - 1;
  std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(rank), d.end());
  error.p95 = d[rank];
  return error;
}

Distortion measure_distortion(const Eigen::Ref<const MatrixX3d>& rest,
                              const Eigen::Ref<const MatrixX3d>& deformed,
                              const Eigen::Ref<const MatrixX3i>& faces) {
  const MatrixX2i edges = unique_edges(faces);
  Distortion out;
  std::size_t counted = 0;
  for (Eigen::Index e = 0; e < edges.rows(); ++e) {
    const double rest_length = (rest.row(edges(e, 0)) - rest.row(edges(e, 1))).norm();
    if (!(rest_length > 0.0)) continue;
    const double length = (deformed.row(edges(e, 0)) - deformed.row(edges(e, 1))).norm();
    const double change = std::abs(length - rest_length) / rest_length;
    out.mean_edge_change += change;
    out.max_edge_change = std::max(out.max_edge_change, change);
    ++counted;
  }
  if (counted > 0) out.mean_edge_change /= static_cast<double>(counted);
  return out;
}

}  // namespace gr
