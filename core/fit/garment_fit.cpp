#include "core/fit/garment_fit.hpp"

#include <algorithm>
#include <vector>

#include "core/mesh/unique_edges.hpp"

namespace gr {

double median_edge_ratio(const TriangleMesh& rest, const Eigen::Ref<const MatrixX3d>& deformed) {
  const MatrixX2i edges = unique_edges(rest.faces);
  std::vector<double> ratios;
  ratios.reserve(static_cast<std::size_t>(edges.rows()));
  for (Eigen::Index e = 0; e < edges.rows(); ++e) {
    const double length = (rest.vertices.row(edges(e, 0)) - rest.vertices.row(edges(e, 1))).norm();
    if (length > 0.0)
      ratios.push_back((deformed.row(edges(e, 0)) - deformed.row(edges(e, 1))).norm() / length);
  }
  if (ratios.empty()) return 1.0;
  const auto middle = ratios.begin() + static_cast<std::ptrdiff_t>(ratios.size() / 2);
  std::nth_element(ratios.begin(), middle, ratios.end());
  return *middle;
}

FitResult fit_garment(const GarmentScene& scene, const Eigen::Ref<const MatrixX3d>& inflated,
                      const RetargetParameters& parameters, Interrupter& interrupter,
                      const GuidePath& guide) {
  RetargetParameters fit_parameters = parameters;
  fit_parameters.dhat = parameters.fit_support();
  GarmentProblem problem(scene, fit_parameters, GarmentProblem::Stage::kFit,
                         median_edge_ratio(scene.garment, inflated));
  Eigen::VectorXd x = problem.layout().pack(1.0, inflated);
  NewtonOptions options = parameters.newton;
  options.max_iterations = parameters.fit_iteration_cap();
  FitResult result;
  if (guide.size > 0) {
    result.guide = follow_guide(problem, x, guide, options);
    // Only a garment that followed the guide to its end is near the end of its fit; one
    // the guide left early fits as it would have without it.
    if (parameters.guided_fit_max_iterations > 0 && result.guide.reached_end)
      options.max_iterations =
          std::min(options.max_iterations, parameters.guided_fit_max_iterations);
  }
  ProjectedNewton newton(options);
  result.solve = newton.minimize(problem, x, interrupter);
  result.garment = problem.layout().garment(x);
  result.fold_free_fraction = problem.contact().mean_fold_free_fraction();
  // minimum_distance finds the contact pairs at x first; the contact term's value needs them.
  result.min_distance = problem.minimum_distance(x);
  result.terms = problem.term_names();
  result.energies = problem.term_values(x);
  result.loop_offsets = problem.loop_offsets(x);
  for (const LoopBone& loop : problem.loop_bones())
    result.loop_sizes.push_back(static_cast<int>(loop.vertices.size()));
  return result;
}

}  // namespace gr
