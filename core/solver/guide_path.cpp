#include "core/solver/guide_path.hpp"

#include <algorithm>

namespace gr {

namespace {
/// A motion that CCD cuts below this fraction ends the following: the path runs into
/// something the guide did not see, which the solve itself must resolve.
constexpr double kSmallestFollowedFraction = 0.1;
}  // namespace

GuideFollowed follow_guide(Problem& problem, Eigen::VectorXd& x, const GuidePath& path) {
  GuideFollowed followed;
  followed.points = path.size;
  Eigen::VectorXd point;
  for (int index = 0; index < path.size; ++index) {
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
        followed.reached_end = false;
        break;
      }
    }
  }
  problem.solution_changed(x);
  return followed;
}

}  // namespace gr
