// Costs of the solver on a real garment (the shared skirt, 2682 vertices): per-iteration
// pieces (surface-energy assembly, CHOLMOD factorization and solve), then a whole
// inflation of the skirt's source body, widened so it pushes through the skirt, from a
// narrowed copy that is free of it. Scene normalized so the body is 2 units tall (Z up).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>

#include "core/common/stopwatch.hpp"
#include "core/energies/surface_shape_energy.hpp"
#include "core/inflation/avatar_inflation.hpp"
#include "core/io/obj_document.hpp"
#include "core/mesh/simulation_mesh.hpp"
#include "core/solver/linear_solver.hpp"
#include "validate/checks/mesh_intersections.hpp"

namespace {

template <typename Work>
double milliseconds(int repeats, Work work) {
  const gr::Stopwatch stopwatch;
  for (int i = 0; i < repeats; ++i) work();
  return stopwatch.milliseconds() / repeats;
}

/// Scales x and y about the vertical axis through the origin.
gr::MatrixX3d scaled_horizontally(const gr::MatrixX3d& V, double factor) {
  gr::MatrixX3d out = V;
  out.leftCols(2) *= factor;
  return out;
}

/// Inflates the skirt's source body (widened by 1.08, so it crosses the skirt) from a
/// narrowed copy free of the skirt, and prints the run.
void inflation_benchmark(const gr::TriangleMesh& garment, gr::TriangleMesh body) {
  gr::GarmentScene scene;
  scene.garment = garment;
  scene.avatar = body;
  scene.avatar.vertices = scaled_horizontally(body.vertices, 1.08);
  const std::size_t crossings = gr::find_intersecting_face_pairs(garment, scene.avatar).count;
  double narrowing = 0.0;
  for (double factor : {0.9, 0.8, 0.7, 0.6, 0.5}) {
    const gr::TriangleMesh shrunk{scaled_horizontally(body.vertices, factor), body.faces};
    if (gr::find_intersecting_face_pairs(garment, shrunk, 1).count == 0) {
      narrowing = factor;
      scene.shrunk_avatar = shrunk.vertices;
      break;
    }
  }
  if (narrowing == 0.0) {
    std::printf("no narrowed body free of the skirt: inflation skipped\n");
    return;
  }
  gr::RetargetParameters parameters;
  std::printf(
      "\ninflation: avatar %d vertices (widened 1.08, %zu face pairs cross the skirt), "
      "A0 narrowed %.1f\n",
      static_cast<int>(body.vertices.rows()), crossings, narrowing);
  std::printf("| round | t | lambda1 | lambda2 | Newton steps | status | seconds |\n");
  std::printf("| --- | --- | --- | --- | --- | --- | --- |\n");
  const gr::InflationResult result =
      gr::inflate_avatar(scene, parameters, [](const gr::InflationRound& r) {
        std::printf("| %d | %.6f | %g | %g | %d | %s | %.2f |\n", r.round, r.t, r.lambda1,
                    r.lambda2, r.solve.iterations, gr::to_string(r.solve.status),
                    r.solve.elapsed_seconds);
      });
  const std::size_t after = gr::find_intersecting_face_pairs(
                                gr::TriangleMesh{result.garment, garment.faces}, scene.avatar)
                                .count;
  std::printf("%s: %s; %d Newton steps in %.2f s (%.1f ms per step); crossings after: %zu\n",
              gr::to_string(result.status), result.message.c_str(), result.newton_iterations,
              result.elapsed_seconds,
              1e3 * result.elapsed_seconds / std::max(result.newton_iterations, 1), after);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string folder =
      argc > 1 ? argv[1] : std::string(GR_SHARED_DATA_DIR) + "/garments/skirt";
  const std::string path = folder + "/garment.obj";
  const std::string body_path = folder + "/source_body.obj";
  if (!std::filesystem::exists(path) || !std::filesystem::exists(body_path)) {
    std::fprintf(stderr, "garment.obj or source_body.obj not found in %s\n", folder.c_str());
    return 1;
  }
  gr::TriangleMesh garment = gr::make_simulation_mesh(gr::read_obj(path)).mesh;
  gr::TriangleMesh body = gr::make_simulation_mesh(gr::read_obj(body_path)).mesh;
  // The body's vertical axis through the origin, its height 2.
  const Eigen::RowVector3d low = body.vertices.colwise().minCoeff();
  const Eigen::RowVector3d high = body.vertices.colwise().maxCoeff();
  const Eigen::RowVector3d centre = 0.5 * (low + high);
  const double scale = 2.0 / (high.z() - low.z());
  garment.vertices = ((garment.vertices.rowwise() - centre) * scale).eval();
  body.vertices = ((body.vertices.rowwise() - centre) * scale).eval();

  const gr::DofLayout layout{static_cast<int>(garment.vertices.rows()), true};
  const gr::SurfaceShapeEnergy energy(garment, layout);
  gr::MatrixX3d V = garment.vertices;
  V.col(2) += 0.05 * V.col(0).cwiseAbs2();  // bend it so the Hessian is not the rest one

  Eigen::VectorXd g;
  const int repeats = 20;
  const double value_ms = milliseconds(repeats, [&] { energy.value(V, 1.0); });
  const double gradient_ms = milliseconds(repeats, [&] { energy.gradient(V, 1.0, g); });
  Eigen::SparseMatrix<double> H;
  const double hessian_ms = milliseconds(repeats, [&] { H = energy.hessian(V, 1.0, true); });
  gr::LinearSolver solver;
  const Eigen::VectorXd shift =
      Eigen::VectorXd::Constant(H.rows(), 1e-8 * H.diagonal().cwiseAbs().maxCoeff());
  const double first_factor_ms = milliseconds(1, [&] { solver.factorize(H, shift); });
  const double factor_ms = milliseconds(repeats, [&] { solver.factorize(H, shift); });
  const double solve_ms = milliseconds(repeats, [&] { solver.solve(g); });

  std::printf(
      "garment %s: %d vertices, %d faces, %zu surface elements, %d dofs, %ld Hessian nonzeros\n",
      path.c_str(), static_cast<int>(garment.vertices.rows()),
      static_cast<int>(garment.faces.rows()), energy.elements().size(), layout.dof_count(),
      static_cast<long>(H.nonZeros()));
  std::printf("| step | ms |\n| --- | --- |\n");
  std::printf(
      "| L_surf value | %.2f |\n| L_surf gradient | %.2f |\n| L_surf Hessian (PSD-projected) | "
      "%.2f |\n",
      value_ms, gradient_ms, hessian_ms);
  std::printf(
      "| CHOLMOD analysis + factorization | %.2f |\n| CHOLMOD factorization (analysis reused) | "
      "%.2f |\n",
      first_factor_ms, factor_ms);
  std::printf("| CHOLMOD solve | %.2f |\n", solve_ms);
  std::printf("symbolic analyses: %d\n", solver.analysis_count());
  inflation_benchmark(garment, body);
  return 0;
}
