#pragma once

#include <functional>

#include <Eigen/Core>

#include "core/solver/problem.hpp"

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
};

/// How far follow_guide came.
struct GuideFollowed {
  int points = 0;          ///< points of the path
  int points_reached = 0;  ///< reached exactly (the motion to them was not cut)
  int cut_motions = 0;     ///< motions CCD cut short
  int held_motions = 0;    ///< motions held back in part (GuidePath::fade_length)
  /// The following went on to the last point (its motions possibly cut short), rather than
  /// ending at a motion cut below a tenth.
  bool reached_end = true;
  bool complete() const { return points_reached == points; }
};

/// Moves x towards each point of `path` in turn along straight motions, each held back in
/// part where it meets something (with path.fade_length) and bounded by problem.max_step
/// (CCD): a motion cut short leaves x where CCD allowed and goes on to the next point from
/// there, and the path is left for good at a motion that CCD lets move less than a tenth
/// of the way (the solve then starts from x). So x stays as safe as the start
/// point, whatever the path: the path only saves the solve's steps.
/// @pre x is a safe point of `problem` (for contact: intersection free).
GuideFollowed follow_guide(Problem& problem, Eigen::VectorXd& x, const GuidePath& path);

}  // namespace gr
