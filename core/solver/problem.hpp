#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace gr {

/// A minimization problem as the projected Newton solver sees it, separate from the solver.
/// The solver calls, per iteration: gradient and hessian at the current point (after
/// solution_changed), then max_step for the Newton direction, then value (and is_valid)
/// at trial points x + alpha dx with alpha no larger than the bound max_step returned.
class Problem {
 public:
  virtual ~Problem() = default;

  virtual int dof_count() const = 0;
  /// Objective at x; +inf (or NaN) where it is not defined.
  virtual double value(const Eigen::VectorXd& x) = 0;
  /// Gradient at x (resized by the callee).
  virtual void gradient(const Eigen::VectorXd& x, Eigen::VectorXd& gradient) = 0;
  /// Hessian at x, projected to positive semi-definite (dof_count², both triangles stored).
  virtual void hessian(const Eigen::VectorXd& x, Eigen::SparseMatrix<double>& hessian) = 0;

  /// Called with each accepted point (and the start point) before gradient and hessian.
  virtual void solution_changed(const Eigen::VectorXd& x) {}
  /// Largest alpha in [0, 1] such that the motion x → x + alpha dx is safe (for contact:
  /// collision free by CCD). Trial points of the line search stay within that bound.
  virtual double max_step(const Eigen::VectorXd& x, const Eigen::VectorXd& dx) { return 1.0; }
  /// Scales a motion dx down part by part where it meets something, so that more of it is
  /// safe than max_step's single fraction would let through: the parts that meet something
  /// are held back, the scaling fading out over `fade_length` (step_length's unit) around
  /// them, and the rest moves in full. max_step still bounds the motion that results.
  /// Default: dx as it is.
  virtual void hold_back(const Eigen::VectorXd& x, Eigen::VectorXd& dx, double fade_length) {}
  /// Whether a trial point may be accepted (besides decreasing the objective).
  virtual bool is_valid(const Eigen::VectorXd& x) { return true; }
  /// Whether x already serves the purpose of the solve, so that it may end short of the
  /// optimum. Asked at the start point and at each accepted point.
  virtual bool goal_reached(const Eigen::VectorXd& x) { return false; }
  /// How far a step dx moves things, in the problem's length unit: the solver's step
  /// tolerance is compared against it. Default: the largest coordinate change.
  virtual double step_length(const Eigen::VectorXd& dx) const {
    return dx.lpNorm<Eigen::Infinity>();
  }
};

}  // namespace gr
