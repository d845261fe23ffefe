#pragma once

#include <limits>
#include <string>

#include "core/common/interrupter.hpp"
#include "core/solver/linear_solver.hpp"
#include "core/solver/problem.hpp"

namespace gr {

/// How a solve ended. Only kConverged means the returned point meets the tolerances.
enum class SolverStatus {
  kConverged,       ///< gradient, Newton step or energy decrease below its tolerance
  kIterationLimit,  ///< max_iterations accepted steps without converging
  kNoDescent,       ///< no step along the search direction lowered the energy (or CCD allowed none)
  kNonFiniteEnergy,  ///< the energy or gradient at the current point is not finite
  kGoalReached,      ///< the problem's goal is met (Problem::goal_reached) before the tolerances
};

const char* to_string(SolverStatus status);

struct NewtonOptions {
  /// Cap on accepted Newton steps.
  int max_iterations = 1000;
  /// eps_tol: converged when the RMS gradient ||g||_2 / sqrt(#dofs) is at most this (energy
  /// per normalized length unit; RMS so that the test does not tighten with mesh size).
  double gradient_tolerance = 1e-8;
  /// Also converged when the full Newton step moves nothing by more than this
  /// (Problem::step_length, normalized scene units): the quadratic model then places the
  /// minimizer within this distance. Garment energies mix stiffnesses over eight orders of
  /// magnitude (contact against shape), which makes a length the more meaningful test.
  double step_tolerance = 1e-6;
  /// Also converged when the energy fell by no more than this fraction of its value over
  /// the last `energy_window` accepted steps (0 turns the test off). Near contact the
  /// barrier's curvature is only seen once pairs come within dhat, so line searches keep
  /// cutting steps far below the Newton step and the gradient and step tests, which look
  /// at one point, are not met for hundreds of steps while the energy barely moves; this
  /// test looks at what the steps achieve instead.
  double energy_tolerance = 0.0;
  int energy_window = 10;
  /// Trust radius: a damped step that would move anything further than this
  /// (Problem::step_length) is scaled down to it before CCD. Raising the damping until the
  /// step fits instead turns the steps towards gradient descent, which jams against
  /// contact (bench/results/parameter_choices.md).
  double max_step_length = std::numeric_limits<double>::infinity();
  /// Halvings of the step in the line search before giving up with kNoDescent.
  int max_line_search_halvings = 50;

  // Levenberg–Marquardt damping. Each step solves (H + mu D) p = -g with D the diagonal of
  // H (Marquardt's scaling, floored at 1e-10 of its mean so that every dof is damped), so
  // the system is positive definite by construction whatever H's null space (rigid motions
  // of a free garment, sliding along the body): the step is a continuous function of the
  // inputs instead of whatever rounding makes of a singular factorization. mu adapts to
  // the ratio rho of the energy's actual to predicted decrease over the step taken (after
  // CCD and the line search; Nielsen's rule): it falls towards min_damping while the
  // quadratic model predicts well, and grows where it does not.
  double initial_damping = 1e-6;
  /// The floor of mu: the relative perturbation of H that every step keeps. At 1e-8 the
  /// scaled system's condition number stays below about 1e10 (a few dozen nonzeros per row
  /// over 1e-8), so rounding moves the step by about 1e-6 of itself, continuously, and the
  /// converged point is unaffected (the damping vanishes with the gradient). A higher floor
  /// can steer the path away from the undamped one (bench/results/
  /// parameter_choices.md).
  double min_damping = 1e-8;
  double max_damping = 1e12;
  /// LinearSolver::set_pattern_slack: Hessian entries outside the analysed pattern that
  /// may be dropped (compensated on the diagonal) instead of redoing the analysis, as a
  /// fraction of the pattern's size. 0 solves with the exact Hessian.
  double pattern_slack = 0.0;

  // Factor reuse. The factorization's cost grows faster than the garment (its operations
  // about as n^1.5 on a surface mesh), while one solve with a held factor grows about as
  // n log n; the Hessian changes little from one step to the next. So when a factorization
  // costs at least `reuse_factor_flops` (CHOLMOD's count for the analysed pattern), the
  // next steps solve their damped system by conjugate gradients preconditioned with the
  // held factor, and factor anew only when that does not reach `reuse_tolerance` within
  // `reuse_max_iterations`. 0 turns it off: every step then factors its own matrix.
  double reuse_factor_flops = 0.0;
  /// Relative residual of a direction solved with a held factor (an inexact Newton step:
  /// the direction's error relative to the exact one is about this times the condition of
  /// the preconditioned system).
  double reuse_tolerance = 1e-3;
  /// Conjugate-gradient iterations before a new factorization is preferred: each costs a
  /// pair of triangular solves, and a dense garment's factorization costs a few dozen of
  /// them (bench/results/dense.md).
  int reuse_max_iterations = 12;
};

struct NewtonResult {
  SolverStatus status = SolverStatus::kNoDescent;
  int iterations = 0;               ///< accepted steps
  double energy = 0.0;              ///< at the returned point
  double gradient_norm = 0.0;       ///< ||g||_2 at the returned point
  double newton_step_length = 0.0;  ///< step_length of the last Newton direction computed
  double damping = 0.0;             ///< mu at the end (relative to H's diagonal)
  int factorizations = 0;           ///< Cholesky factorizations, all steps
  int reused_factor_steps = 0;      ///< directions solved with a held factor (no factorization)
  int cg_iterations = 0;            ///< conjugate-gradient iterations of those directions
  int gradient_descent_steps = 0;   ///< directions taken from -g after factorization failures
  double elapsed_seconds = 0.0;
  std::string message;  ///< one line saying why the solve stopped
  bool converged() const { return status == SolverStatus::kConverged; }
};

/// Projected Newton (Algorithm 2 of the supplement) with Levenberg–Marquardt damping: Hessian
/// from the problem (projected per element), direction from CHOLMOD on the damped system
/// (see NewtonOptions), bounded by the trust radius and by the problem's max_step (CCD),
/// halved until the energy does not increase, stop on the tolerances (gradient, Newton step,
/// energy decrease over a window of steps) or the iteration cap.
/// Keeps its factorization and its damping between solves, so repeated solves (the rounds
/// of the inflation) reuse the symbolic analysis and start from the damping the last one
/// reached.
class ProjectedNewton {
 public:
  explicit ProjectedNewton(NewtonOptions options = {}) : options_(options) {}

  const NewtonOptions& options() const { return options_; }
  NewtonOptions& options() { return options_; }
  const LinearSolver& linear_solver() const { return linear_solver_; }

  /// Minimizes from x; x is overwritten with the last accepted point whatever the status.
  /// After each accepted step asks `interrupter` whether to stop (check()), then reports
  /// the step to it (Interrupter::step).
  /// @throw Interrupted from `interrupter`; x then holds the last accepted point.
  NewtonResult minimize(Problem& problem, Eigen::VectorXd& x,
                        Interrupter& interrupter = null_interrupter());

 private:
  /// The damped direction -(H + mu D)⁻¹g within the trust radius, raising mu while the
  /// factorization fails; false when even max_damping failed.
  bool damped_direction(Problem& problem, const Eigen::SparseMatrix<double>& H,
                        const Eigen::VectorXd& g, Eigen::VectorXd& direction, NewtonResult& result);
  /// The damped direction by conjugate gradients on the held factor (NewtonOptions' factor
  /// reuse); false when reuse does not apply or does not converge.
  bool reused_factor_direction(const Eigen::SparseMatrix<double>& H, const Eigen::VectorXd& g,
                               const Eigen::VectorXd& scale, Eigen::VectorXd& direction,
                               NewtonResult& result);
  /// The damped direction from a new factorization, raising mu while it fails; false when
  /// even max_damping failed.
  bool factored_direction(const Eigen::SparseMatrix<double>& H, const Eigen::VectorXd& g,
                          const Eigen::VectorXd& scale, Eigen::VectorXd& direction,
                          NewtonResult& result);
  /// Scales the direction down to the trust radius (max_step_length).
  void clip_to_trust_radius(Problem& problem, Eigen::VectorXd& direction) const;
  /// Nielsen's update of mu from the ratio of actual to predicted decrease.
  void update_damping(double ratio);

  NewtonOptions options_;
  LinearSolver linear_solver_;
  double damping_ = -1.0;              ///< mu; negative until the first solve sets it
  double damping_growth_ = 2.0;        ///< Nielsen's nu: how much the next rejection raises mu
  int reuse_skips_left_ = 0;           ///< steps that factor without trying the held factor first
  int reuse_skips_after_failure_ = 0;  ///< reuse_skips_left_ after the next failed reuse
};

}  // namespace gr
