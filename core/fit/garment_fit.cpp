#include "core/fit/garment_fit.hpp"

namespace gr {

FitResult fit_garment(const GarmentScene& scene, const Eigen::Ref<const MatrixX3d>& inflated,
                      const RetargetParameters& parameters, const NewtonCallback& on_newton_step) {
  RetargetParameters fit_parameters = parameters;
  fit_parameters.dhat = parameters.fit_support();
  GarmentProblem problem(scene, fit_parameters, GarmentProblem::Stage::kFit);
  Eigen::VectorXd x = problem.layout().pack(1.0, inflated);
  ProjectedNewton newton(parameters.newton);
  FitResult result;
  result.solve = newton.minimize(problem, x, on_newton_step);
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
