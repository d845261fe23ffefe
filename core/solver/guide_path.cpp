#include "core/solver/guide_path.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/SparseCore>

namespace gr {

namespace {
/// A motion that CCD cuts below this fraction ends the following, unless a recovery lets
/// it through: the path runs into something the guide did not see.
constexpr double kSmallestFollowedFraction = 0.1;
/// Recoveries before the path is left, at one point and along the whole path: each costs
/// up to GuidePath::recovery_steps Newton steps of the full problem.
constexpr int kRecoveriesPerPoint = 2;
constexpr int kRecoveriesPerPath = 8;
/// The spring's stiffness over the median of the objective's curvature per dof: where
/// nothing is met, a Newton step of the pulled problem goes about four fifths of the way
/// to the point. The same on every dof: one scaled by the curvature there would be as
/// stiff as the barrier of what it met, and pull straight into it.
constexpr double kPullStiffness = 4.0;

/// The problem plus a spring to a point, k/2 |x - p|^2; safety (CCD, hold back, validity)
/// is the problem's own.
class PulledProblem : public Problem {
 public:
  PulledProblem(Problem& problem, const Eigen::VectorXd& point, double stiffness)
      : problem_(problem), point_(point), stiffness_(stiffness) {
    spring_.resize(point.size(), point.size());
    spring_.setIdentity();
    spring_ *= stiffness;
  }

  int dof_count() const override { return problem_.dof_count(); }
  double value(const Eigen::VectorXd& x) override {
    return problem_.value(x) + 0.5 * stiffness_ * (x - point_).squaredNorm();
  }
  void gradient(const Eigen::VectorXd& x, Eigen::VectorXd& gradient) override {
    problem_.gradient(x, gradient);
    gradient += stiffness_ * (x - point_);
  }
  void hessian(const Eigen::VectorXd& x, Eigen::SparseMatrix<double>& hessian) override {
    problem_.hessian(x, hessian);
    hessian += spring_;
  }
  void solution_changed(const Eigen::VectorXd& x) override { problem_.solution_changed(x); }
  double max_step(const Eigen::VectorXd& x, const Eigen::VectorXd& dx) override {
    return problem_.max_step(x, dx);
  }
  void hold_back(const Eigen::VectorXd& x, Eigen::VectorXd& dx, double fade_length) override {
    problem_.hold_back(x, dx, fade_length);
  }
  bool is_valid(const Eigen::VectorXd& x) override { return problem_.is_valid(x); }
  double step_length(const Eigen::VectorXd& dx) const override { return problem_.step_length(dx); }

 private:
  Problem& problem_;
  const Eigen::VectorXd& point_;
  double stiffness_;
  Eigen::SparseMatrix<double> spring_;
};

/// Pulls x towards `point` with at most `steps` Newton steps (follow_guide); false when the
/// objective has no curvature at x to scale the spring by.
bool recover(Problem& problem, Eigen::VectorXd& x, const Eigen::VectorXd& point, int steps,
             const NewtonOptions& newton, GuideFollowed& followed) {
  problem.solution_changed(x);
  Eigen::SparseMatrix<double> hessian;
  problem.hessian(x, hessian);
  const Eigen::VectorXd diagonal = hessian.diagonal();
  std::vector<double> curvature(diagonal.data(), diagonal.data() + diagonal.size());
  if (curvature.empty()) return false;
  const auto middle = curvature.begin() + static_cast<std::ptrdiff_t>(curvature.size() / 2);
  std::nth_element(curvature.begin(), middle, curvature.end());
  if (!(*middle > 0.0) || !std::isfinite(*middle)) return false;

  PulledProblem pulled(problem, point, kPullStiffness * *middle);
  NewtonOptions options = newton;
  options.max_iterations = steps;
  ProjectedNewton solver(options);
  const NewtonResult solve = solver.minimize(pulled, x);
  ++followed.recoveries;
  followed.recovery_steps += solve.iterations;
  return true;
}

}  // namespace

GuideFollowed follow_guide(Problem& problem, Eigen::VectorXd& x, const GuidePath& path,
                           const NewtonOptions& newton) {
  GuideFollowed followed;
  followed.points = path.size;
  Eigen::VectorXd point;
  int recoveries_here = 0;
  for (int index = 0; index < path.size;) {
    path.point(index, point);
    Eigen::VectorXd motion = point - x;
    double alpha = std::min(1.0, problem.max_step(x, motion));
    bool held = false;
    if (alpha < 1.0 && path.fade_length > 0.0) {
      const Eigen::VectorXd whole = motion;
      problem.hold_back(x, motion, path.fade_length);
      held = motion != whole;
      if (held) {
        ++followed.held_motions;
        alpha = std::min(1.0, problem.max_step(x, motion));
      }
    }
    if (alpha >= 1.0) {
      if (held) {
        x += motion;
      } else {
        x = point;
        ++followed.points_reached;
      }
    } else {
      ++followed.cut_motions;
      if (alpha > 0.0) x += alpha * motion;
      if (alpha < kSmallestFollowedFraction) {
        if (path.recovery_steps > 0 && recoveries_here < kRecoveriesPerPoint &&
            followed.recoveries < kRecoveriesPerPath &&
            recover(problem, x, point, path.recovery_steps, newton, followed)) {
          ++recoveries_here;
          continue;  // the same point again, from where the recovery led
        }
        followed.reached_end = false;
        break;
      }
    }
    ++index;
    recoveries_here = 0;
  }
  problem.solution_changed(x);
  return followed;
}

}  // namespace gr
