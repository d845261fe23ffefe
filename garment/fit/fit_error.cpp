#include "garment/fit/fit_error.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

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

}  // namespace gr
