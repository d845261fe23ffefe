#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/SparseCore>

#include "core/solver/guide_path.hpp"

using namespace gr;

namespace {

/// One coordinate that must stay below a wall: max_step keeps a tenth of the gap, as a
/// CCD that leaves a separation does, and counts the points it was shown.
class WallProblem : public Problem {
 public:
  explicit WallProblem(double wall) : wall_(wall) {}
  int dof_count() const override { return 1; }
  double value(const Eigen::VectorXd& x) override { return x[0] < wall_ ? 0.0 : INFINITY; }
  void gradient(const Eigen::VectorXd&, Eigen::VectorXd& g) override { g.setZero(1); }
  void hessian(const Eigen::VectorXd&, Eigen::SparseMatrix<double>& H) override { H.resize(1, 1); }
  double max_step(const Eigen::VectorXd& x, const Eigen::VectorXd& dx) override {
    if (x[0] + dx[0] < wall_) return 1.0;
    return 0.9 * (wall_ - x[0]) / dx[0];
  }
  void solution_changed(const Eigen::VectorXd& x) override { changed_at.push_back(x[0]); }
  std::vector<double> changed_at;

 private:
  double wall_;
};

/// A path through `points`, each point with that value in all of its `dofs` coordinates.
GuidePath path_through(const std::vector<double>& points, int dofs = 1) {
  return {static_cast<int>(points.size()), [points, dofs](int index, Eigen::VectorXd& point) {
            point = Eigen::VectorXd::Constant(dofs, points[static_cast<std::size_t>(index)]);
          }};
}

}  // namespace

TEST_CASE("follow_guide: a clear path is followed to its end", "[solver][guide]") {
  WallProblem problem(10.0);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(1);
  const GuideFollowed followed = follow_guide(problem, x, path_through({1.0, 3.0, 2.0, 5.0}));
  CHECK(followed.points == 4);
  CHECK(followed.points_reached == 4);
  CHECK(followed.cut_motions == 0);
  CHECK(followed.complete());
  CHECK(followed.reached_end);
  CHECK(x[0] == 5.0);
  // The problem hears of the end point before a solve starts from it.
  REQUIRE_FALSE(problem.changed_at.empty());
  CHECK(problem.changed_at.back() == 5.0);
}

TEST_CASE("follow_guide: a path through a wall stops short of it", "[solver][guide]") {
  WallProblem problem(1.0);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(1);
  // The third motion is cut to 0.9 of the gap (0.8 → 0.98, a fraction 0.15 of it); the
  // next one, towards 2, can only move 0.9 of the remaining 0.02 (a fraction 0.018 of it),
  // which ends the following.
  const GuideFollowed followed = follow_guide(problem, x, path_through({0.5, 0.8, 2.0, 2.0, 0.0}));
  CAPTURE(x[0]);
  CHECK(followed.points == 5);
  CHECK(followed.points_reached == 2);
  CHECK(followed.cut_motions == 2);
  CHECK_FALSE(followed.complete());
  CHECK_FALSE(followed.reached_end);
  CHECK(x[0] < 1.0);
  CHECK(x[0] == Approx(0.8 + 0.9 * 0.2 + 0.9 * (1.0 - 0.98)).epsilon(1e-12));
  // The last point (back at 0) is never taken: the following ended at the wall.
  CHECK(x[0] > 0.9);
}

TEST_CASE("follow_guide: motions cut by a little still reach the path's end", "[solver][guide]") {
  WallProblem problem(1.0);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(1);
  // Towards 1.5 from 0: cut to 0.9 of the gap (0.9, a fraction 0.6); then back to 0.2.
  const GuideFollowed followed = follow_guide(problem, x, path_through({1.5, 0.2}));
  CHECK(followed.points_reached == 1);
  CHECK(followed.cut_motions == 1);
  CHECK_FALSE(followed.complete());
  CHECK(followed.reached_end);
  CHECK(x[0] == 0.2);
}

TEST_CASE("follow_guide: an empty path leaves the point", "[solver][guide]") {
  WallProblem problem(1.0);
  Eigen::VectorXd x = Eigen::VectorXd::Constant(1, 0.25);
  const GuideFollowed followed = follow_guide(problem, x, GuidePath());
  CHECK(followed.points == 0);
  CHECK(followed.complete());
  CHECK(x[0] == 0.25);
}

namespace {

/// Two coordinates, the first below a wall and the second free: hold_back keeps the
/// first's motion within 0.9 of its gap and lets the second move in full.
class HalfWallProblem : public WallProblem {
 public:
  explicit HalfWallProblem(double wall) : WallProblem(wall), wall_(wall) {}
  int dof_count() const override { return 2; }
  void hold_back(const Eigen::VectorXd& x, Eigen::VectorXd& dx, double fade_length) override {
    fade_lengths.push_back(fade_length);
    if (x[0] + dx[0] >= wall_) dx[0] = 0.9 * (wall_ - x[0]);
  }
  std::vector<double> fade_lengths;

 private:
  double wall_;
};

}  // namespace

TEST_CASE("follow_guide: a motion held back in part lets the rest follow to the end",
          "[solver][guide]") {
  HalfWallProblem problem(1.0);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(2);
  GuidePath path = path_through({0.5, 2.0, 3.0}, 2);
  path.fade_length = 0.25;
  const GuideFollowed followed = follow_guide(problem, x, path);
  CHECK(followed.points_reached == 1);
  CHECK(followed.held_motions == 2);
  CHECK(followed.cut_motions == 0);
  CHECK(followed.reached_end);
  CHECK(x[1] == 3.0);  // the free part is where the path ends
  CHECK(x[0] < 1.0);   // the held part never reaches the wall
  CHECK(x[0] == Approx(0.5 + 0.9 * 0.5 + 0.9 * 0.05).epsilon(1e-12));
  // Asked only for the motions CCD would cut.
  CHECK(problem.fade_lengths == std::vector<double>{0.25, 0.25});

  // Without a fade length the motion is cut as a whole, and the path is soon left.
  HalfWallProblem whole(1.0);
  Eigen::VectorXd y = Eigen::VectorXd::Zero(2);
  const GuideFollowed cut = follow_guide(whole, y, path_through({0.5, 2.0, 3.0}, 2));
  CHECK(whole.fade_lengths.empty());
  CHECK(cut.held_motions == 0);
  CHECK(cut.cut_motions == 2);
  CHECK_FALSE(cut.reached_end);
  CHECK(y[1] < 1.0);
}

namespace {

/// A point in the plane kept out of the unit disc by a log barrier on its distance d to
/// the circle, -(d - h)^2 ln(d / h) within h = 0.5 (its Hessian projected: the normal
/// part). max_step keeps a tenth of the gap to the circle along the motion, as a CCD
/// that leaves a separation does.
class DiscProblem : public Problem {
 public:
  int dof_count() const override { return 2; }
  double value(const Eigen::VectorXd& x) override {
    const double d = x.norm() - 1.0;
    if (!(d > 0.0)) return INFINITY;
    return d < kReach ? -(d - kReach) * (d - kReach) * std::log(d / kReach) : 0.0;
  }
  void gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) override {
    const double d = x.norm() - 1.0;
    g = d < kReach ? Eigen::VectorXd(slope(d) * x.normalized()) : Eigen::VectorXd::Zero(2);
  }
  void hessian(const Eigen::VectorXd& x, Eigen::SparseMatrix<double>& H) override {
    const double d = x.norm() - 1.0;
    const Eigen::Vector2d n = x.normalized();
    const double c = d < kReach ? curvature(d) : 0.0;
    const Eigen::Matrix2d dense = std::max(c, 0.0) * n * n.transpose();
    std::vector<Eigen::Triplet<double>> entries;
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) entries.emplace_back(i, j, dense(i, j));
    H.resize(2, 2);
    H.setFromTriplets(entries.begin(), entries.end());
  }
  double max_step(const Eigen::VectorXd& x, const Eigen::VectorXd& dx) override {
    // |x + s dx|^2 = 1: the first root in [0, 1], if any.
    const double a = dx.squaredNorm(), b = 2.0 * x.dot(dx), c = x.squaredNorm() - 1.0;
    const double discriminant = b * b - 4.0 * a * c;
    if (!(a > 0.0) || discriminant < 0.0) return 1.0;
    const double s = (-b - std::sqrt(discriminant)) / (2.0 * a);
    return s >= 0.0 && s <= 1.0 ? 0.9 * s : 1.0;
  }
  void solution_changed(const Eigen::VectorXd& x) override {
    closest = std::min(closest, x.norm());
  }
  double closest = INFINITY;  ///< the smallest |x| among the points the problem was shown

 private:
  static constexpr double kReach = 0.5;
  static double slope(double d) {
    return -2.0 * (d - kReach) * std::log(d / kReach) - (d - kReach) * (d - kReach) / d;
  }
  static double curvature(double d) {
    return -2.0 * std::log(d / kReach) - 4.0 * (d - kReach) / d +
           (d - kReach) * (d - kReach) / (d * d);
  }
};

}  // namespace

TEST_CASE("follow_guide: a motion stopped by an obstacle recovers around it", "[solver][guide]") {
  DiscProblem problem;
  GuidePath path;
  // In front of the disc, then behind it (the motion there is cut at once), then on.
  path.size = 3;
  path.point = [](int index, Eigen::VectorXd& point) {
    point =
        Eigen::Vector2d(std::vector<double>{-1.3, 2.0, 2.5}[static_cast<std::size_t>(index)], 0.3);
  };
  SECTION("with recovery steps, the point slides around the disc and the path goes on") {
    path.recovery_steps = 8;
    Eigen::VectorXd x = Eigen::Vector2d(-2.0, 0.3);
    const GuideFollowed followed = follow_guide(problem, x, path);
    CAPTURE(x.transpose(), followed.recovery_steps);
    CHECK(followed.recoveries >= 1);
    CHECK(followed.recovery_steps >= 1);
    CHECK(followed.reached_end);
    CHECK(followed.points_reached == 3);
    CHECK(x == Eigen::Vector2d(2.5, 0.3));
    CHECK(problem.closest > 1.0);
  }
  SECTION("without, the path is left in front of the disc") {
    Eigen::VectorXd x = Eigen::Vector2d(-2.0, 0.3);
    const GuideFollowed followed = follow_guide(problem, x, path);
    CHECK(followed.recoveries == 0);
    CHECK_FALSE(followed.reached_end);
    CHECK(x[0] < -0.9);
  }
  SECTION("straight at the disc's centre nothing slides: two recoveries, then it is left") {
    path.recovery_steps = 8;
    path.point = [](int, Eigen::VectorXd& point) { point = Eigen::Vector2d(2.0, 0.0); };
    Eigen::VectorXd x = Eigen::Vector2d(-2.0, 0.0);
    const GuideFollowed followed = follow_guide(problem, x, path);
    CHECK(followed.recoveries == 2);
    CHECK_FALSE(followed.reached_end);
    CHECK(x[0] < -1.0);
    CHECK(problem.closest > 1.0);
  }
}
