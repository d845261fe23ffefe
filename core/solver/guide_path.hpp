#pragma once

#include <functional>

#include <Eigen/Core>

#include "core/solver/problem.hpp"
#include "core/solver/projected_newton.hpp"

namespace gr {

/// Points for a solve to pass through before it minimizes, in the problem's dofs. A coarse
/// solve's iterates carried to a fine mesh make one, so that the fine solve starts near its
/// end.
struct GuidePath {
  int size = 0;
  /// Writes the `index`-th point (0 <= index < size) to `point`.
  std::function<void(int index, Eigen::VectorXd& point)> point;
  /// > 0: each motion is held back where it meets something (Problem::hold_back, fading
  /// out over this length), so that the rest follows the path in full; 0: a motion is cut
  /// short as a whole.
  double fade_length = 0.0;
  /// > 0: a motion cut below a tenth does not end the following at once. Up to this many
  /// Newton steps of the problem pulled towards the point (follow_guide) first move x
  /// around what stopped it, and the motion is tried again; 0: the path is left there.
  int recovery_steps = 0;
};

/// How far follow_guide came.
struct GuideFollowed {
  int points = 0;          ///< points of the path
  int points_reached = 0;  ///< reached exactly (the motion to them was not cut)
  int cut_motions = 0;     ///< motions CCD cut short
  int held_motions = 0;    ///< motions held back in part (GuidePath::fade_length)
  int recoveries = 0;      ///< pulled solves after a cut motion (GuidePath::recovery_steps)
  int recovery_steps = 0;  ///< their Newton steps, all recoveries
  /// The following went on to the last point (its motions possibly cut short), rather than
  /// ending at a motion cut below a tenth.
  bool reached_end = true;
  bool complete() const { return points_reached == points; }
};

/// Moves x towards each point of `path` in turn along straight motions, each held back in
/// part where it meets something (with path.fade_length) and bounded by problem.max_step
/// (CCD): a motion cut short leaves x where CCD allowed and goes on to the next point from
/// there. A motion that CCD lets move less than a tenth of the way is first recovered
/// from (with path.recovery_steps): projected Newton, with `newton`'s options and at most
/// that many steps, minimizes the problem's objective plus a spring to the point, as stiff
/// on every dof as four times the median over the dofs of the objective's curvature, so
/// that where something is met its barrier outweighs the spring and x slides around it
/// towards the point; then the motion is tried again, twice at most per point and eight
/// times along the path. Where it is still cut below a tenth, the path is left for good
/// (the solve then starts from x). So x stays as safe as the start point, whatever the
/// path: the path only saves the solve's steps.
/// @pre x is a safe point of `problem` (for contact: intersection free).
GuideFollowed follow_guide(Problem& problem, Eigen::VectorXd& x, const GuidePath& path,
                           const NewtonOptions& newton = {});

}  // namespace gr
