#include <catch2/catch.hpp>

#include <algorithm>

#include "core/energies/analytic_fields.hpp"
#include "core/energies/energy_checks.hpp"
#include "core/inflation/garment_problem.hpp"
#include "core/test_shapes.hpp"

using namespace gr;

namespace {

/// Avatar icosphere (radius 1, shrunk 0.9) and a garment with the same connectivity just
/// outside A(0.5) (radius 0.95): every garment face is within dhat of the avatar at t = 0.5.
GarmentScene close_contact_scene() {
  GarmentScene scene;
  scene.avatar = icosphere(1, 1.0);
  scene.shrunk_avatar = 0.9 * scene.avatar.vertices;
  scene.garment = icosphere(1, 0.9512);
  return scene;
}

/// Checks the problem's gradient and exact Hessian at x against central differences.
void check_problem_derivatives(GarmentProblem& problem, const Eigen::VectorXd& x, double h) {
  problem.solution_changed(x);
  REQUIRE(problem.contact().candidates().size() > 0);
  const auto f = [&](const Eigen::VectorXd& y) { return problem.value(y); };
  const auto grad = [&](const Eigen::VectorXd& y) {
    Eigen::VectorXd g;
    problem.gradient(y, g);
    return g;
  };
  Eigen::VectorXd g;
  problem.gradient(x, g);
  CHECK(test::fd_matches(g, test::fd_gradient(f, x, h), 1e-5));
  Eigen::SparseMatrix<double> H;
  problem.hessian_of(x, H, false);
  CHECK(test::fd_matches(Eigen::MatrixXd(H), test::fd_hessian(grad, x, h), 1e-5));
}

}  // namespace

TEST_CASE("garment problem: inflation derivatives over [t, Vg] with contact, AL and L_pos",
          "[inflation][grad][hess]") {
  GarmentScene scene = close_contact_scene();
  // A vertical skeleton through the sphere; the garment is closed, so give it loops by
  // opening it: drop the faces around one vertex.
  SkeletonMotion skeletons;
  skeletons.source_joints.resize(2, 3);
  skeletons.source_joints << 0, 0, -1.2, 0, 0, 1.2;
  skeletons.target_joints = 1.1 * skeletons.source_joints;
  skeletons.target_joints(0, 0) += 0.05;
  skeletons.bones.resize(1, 2);
  skeletons.bones << 0, 1;
  scene.skeletons = skeletons;
  MatrixX3i open_faces(scene.garment.faces.rows(), 3);
  int kept = 0;
  const int top = [&] {
    Eigen::Index i;
    scene.garment.vertices.col(2).maxCoeff(&i);
    return static_cast<int>(i);
  }();
  for (int f = 0; f < scene.garment.faces.rows(); ++f)
    if ((scene.garment.faces.row(f).array() != top).all())
      open_faces.row(kept++) = scene.garment.faces.row(f);
  scene.garment.faces = open_faces.topRows(kept);

  RetargetParameters parameters;
  GarmentProblem problem(scene, parameters, GarmentProblem::Stage::kInflation);
  REQUIRE(problem.loop_bones().size() == 1);
  // With skeletons L_pos holds size and place; the skeleton-free terms stay out.
  const std::vector<std::string> names = problem.term_names();
  CHECK(std::count(names.begin(), names.end(), "position") == 1);
  CHECK(std::count(names.begin(), names.end(), "stretch") == 0);
  CHECK(std::count(names.begin(), names.end(), "anchor") == 0);
  problem.constraint().lambda1 = 8.0;
  problem.constraint().lambda2 = 3.0;
  std::srand(3);
  Eigen::VectorXd x = problem.layout().pack(0.5, scene.garment.vertices);
  x.tail(x.size() - 1) += 2e-4 * Eigen::VectorXd::Random(x.size() - 1);
  check_problem_derivatives(problem, x, 1e-8);
}

TEST_CASE("garment problem: fit derivatives over Vg with contact and L_fit", "[fit][grad][hess]") {
  GarmentScene scene = close_contact_scene();
  scene.shrunk_avatar = 0.95 * scene.avatar.vertices;
  scene.garment.vertices *= 1.0012 / 0.9512;  // radius 1.0012: within dhat of A
  const test::SphereField field(Vector3d::Zero(), 0.98);
  scene.distance_field = &field;
  RetargetParameters parameters;
  GarmentProblem problem(scene, parameters, GarmentProblem::Stage::kFit);
  REQUIRE(problem.dof_count() == 3 * scene.garment.vertices.rows());
  // No skeletons: the fit holds the garment's edge lengths and boundary loops instead.
  const std::vector<std::string> names = problem.term_names();
  CHECK(std::count(names.begin(), names.end(), "stretch") == 1);
  CHECK(std::count(names.begin(), names.end(), "anchor") == 1);
  CHECK(std::count(names.begin(), names.end(), "position") == 0);
  std::srand(4);
  Eigen::VectorXd x = problem.layout().pack(1.0, scene.garment.vertices);
  x += 2e-4 * Eigen::VectorXd::Random(x.size());
  check_problem_derivatives(problem, x, 1e-8);
}

TEST_CASE("garment problem: step length counts the avatar's motion through t", "[inflation]") {
  const GarmentScene scene = close_contact_scene();
  GarmentProblem problem(scene, RetargetParameters{}, GarmentProblem::Stage::kInflation);
  Eigen::VectorXd dx = Eigen::VectorXd::Zero(problem.dof_count());
  dx[0] = 0.5;  // t: the avatar moves 0.5 · |A - A0| = 0.05
  CHECK(problem.step_length(dx) == Approx(0.05));
  dx[4] = 0.2;
  CHECK(problem.step_length(dx) == Approx(0.2));
}

TEST_CASE("garment problem: the fit holds back only where a motion meets the avatar",
          "[fit][ccd]") {
  // A flat patch above a unit sphere, moved down by 0.2: its middle would pass into the
  // sphere, its corners (1.13 from the axis) pass beside it.
  GarmentScene scene;
  scene.avatar = icosphere(3, 1.0);
  scene.shrunk_avatar = 0.9 * scene.avatar.vertices;
  const int cells = 16;
  scene.garment = quad_grid(cells, cells, false, [&](int i, int j) {
    return Vector3d(-0.8 + 1.6 * j / cells, -0.8 + 1.6 * i / cells, 1.1);
  });
  const test::SphereField field(Vector3d::Zero(), 1.0);
  scene.distance_field = &field;
  GarmentProblem problem(scene, RetargetParameters{}, GarmentProblem::Stage::kFit);
  const Eigen::VectorXd x = problem.layout().pack(1.0, scene.garment.vertices);
  Eigen::VectorXd dx = Eigen::VectorXd::Zero(x.size());
  for (Eigen::Index v = 0; v < scene.garment.vertices.rows(); ++v)
    dx[problem.layout().vertex_dof(static_cast<int>(v), 2)] = -0.2;
  REQUIRE(problem.max_step(x, dx) < 1.0);

  Eigen::VectorXd held = dx;
  const double fade = 0.2;
  problem.hold_back(x, held, fade);
  CHECK(problem.max_step(x, held) == 1.0);  // what is left is safe in full
  const int middle = cells / 2 * (cells + 1) + cells / 2;
  const int corner = 0;
  CHECK(held[problem.layout().vertex_dof(middle, 2)] > -0.1);   // stays above the sphere
  CHECK(held[problem.layout().vertex_dof(corner, 2)] == -0.2);  // beyond the fade: in full
  // Held back by a scale: nothing moves sideways or further than asked.
  for (Eigen::Index k = 0; k < dx.size(); ++k) {
    CHECK(held[k] * dx[k] >= 0.0);
    CHECK(std::abs(held[k]) <= std::abs(dx[k]));
  }

  // In the inflation the avatar moves with t: only garment–garment pairs hold the garment
  // back, so a motion that meets the avatar alone is left as it is.
  GarmentScene inflating = scene;
  inflating.shrunk_avatar = 0.5 * scene.avatar.vertices;
  GarmentProblem inflation(inflating, RetargetParameters{}, GarmentProblem::Stage::kInflation);
  const Eigen::VectorXd start = inflation.layout().pack(0.0, scene.garment.vertices);
  Eigen::VectorXd motion = Eigen::VectorXd::Zero(start.size());
  motion[0] = 1.0;
  Eigen::VectorXd kept = motion;
  inflation.hold_back(start, kept, fade);
  CHECK(kept == motion);
}

TEST_CASE("garment problem: tangle pairs pressed together are those modelled from the start",
          "[garment_problem]") {
  // A quad crossing a flap (faces 0-1 and 2-3), all in one tangle: vertex 6 lies on the quad
  // from the start (its pairs are not modelled), vertex 7 lies 1e-3 above it.
  GarmentScene scene;
  scene.garment.vertices.resize(8, 3);
  scene.garment.vertices << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0.5, 0.5, -0.2, 0.5, 0.5, 0.2, 0.3,
      0.2, 0, 0.3, 0.7, 1e-3;
  scene.garment.faces.resize(4, 3);
  scene.garment.faces << 0, 1, 2, 0, 2, 3, 4, 5, 6, 5, 7, 6;
  scene.avatar = icosphere(1, 0.1);
  scene.avatar.vertices.rowwise() += RowVector3d(5.0, 5.0, 5.0);
  scene.shrunk_avatar = scene.avatar.vertices;
  RetargetParameters parameters;
  parameters.dhat = 0.01;
  const double gap = 0.01 * parameters.dhat;
  MatrixX3d pressed = scene.garment.vertices;
  pressed(7, 2) = 1e-6;

  SECTION("without tangles nothing counts") {
    CHECK(pressed_tangle_pairs(scene, parameters, pressed, gap) == 0);
  }
  scene.garment_tangles.assign(8, 0);
  // The flap's face 2 crosses both quad faces (edge 4-5 through their diagonal), face 3
  // touches face 0 at vertex 6.
  scene.garment_crossing_faces = {{0, 2}, {0, 3}, {1, 2}};
  SECTION("as given, only the pairs left out from the start are that close") {
    CHECK(pressed_tangle_pairs(scene, parameters, scene.garment.vertices, gap) == 0);
  }
  SECTION("vertex 7 pressed onto the quad") {
    CHECK(pressed_tangle_pairs(scene, parameters, pressed, gap) >= 1);
    // Lower than given, but every pair of vertex 7 (edge 6-7 over the quad's diagonal at a
    // fifth of its height) further than the gap.
    pressed(7, 2) = 8.0 * gap;
    CHECK(pressed_tangle_pairs(scene, parameters, pressed, gap) == 0);
  }
  SECTION("in two tangles, the pair between them is not one tangle's") {
    scene.garment_tangles = {0, 0, 0, 0, 1, 1, 1, 1};
    CHECK(pressed_tangle_pairs(scene, parameters, pressed, gap) == 0);
  }
}
