// Per-iteration costs of the solver's pieces on a real garment (the shared skirt, 2682
// vertices, normalized to 2 units): surface-energy assembly (value, gradient, projected
// Hessian) and the CHOLMOD factorization and solve of that Hessian.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>

#include "core/energies/surface_shape_energy.hpp"
#include "core/io/obj_document.hpp"
#include "core/mesh/simulation_mesh.hpp"
#include "core/solver/linear_solver.hpp"

namespace {

template <typename Work>
double milliseconds(int repeats, Work work) {
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < repeats; ++i) work();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() /
         repeats;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1] : std::string(GR_SHARED_DATA_DIR) + "/garments/skirt/garment.obj";
  if (!std::filesystem::exists(path)) {
    std::fprintf(stderr, "garment not found: %s\n", path.c_str());
    return 1;
  }
  gr::TriangleMesh garment = gr::make_simulation_mesh(gr::read_obj(path)).mesh;
  const Eigen::RowVector3d low = garment.vertices.colwise().minCoeff();
  const Eigen::RowVector3d high = garment.vertices.colwise().maxCoeff();
  garment.vertices = ((garment.vertices.rowwise() - 0.5 * (low + high)) * (2.0 / (high - low).maxCoeff())).eval();

  const gr::DofLayout layout{static_cast<int>(garment.vertices.rows()), true};
  const gr::SurfaceShapeEnergy energy(garment, layout);
  gr::MatrixX3d V = garment.vertices;
  V.col(2) += 0.05 * V.col(0).cwiseAbs2();  // bend it so the Hessian is not the rest one

  Eigen::VectorXd g;
  const int repeats = 20;
  const double value_ms = milliseconds(repeats, [&] { energy.value(V); });
  const double gradient_ms = milliseconds(repeats, [&] { energy.gradient(V, g); });
  Eigen::SparseMatrix<double> H;
  const double hessian_ms = milliseconds(repeats, [&] { H = energy.hessian(V, true); });
  gr::LinearSolver solver;
  const double shift = 1e-8 * H.diagonal().cwiseAbs().maxCoeff();
  const double first_factor_ms = milliseconds(1, [&] { solver.factorize(H, shift); });
  const double factor_ms = milliseconds(repeats, [&] { solver.factorize(H, shift); });
  const double solve_ms = milliseconds(repeats, [&] { solver.solve(g); });

  std::printf("garment %s: %d vertices, %d faces, %zu surface elements, %d dofs, %ld Hessian nonzeros\n",
              path.c_str(), static_cast<int>(garment.vertices.rows()), static_cast<int>(garment.faces.rows()),
              energy.elements().size(), layout.dof_count(), static_cast<long>(H.nonZeros()));
  std::printf("| step | ms |\n| --- | --- |\n");
  std::printf("| L_surf value | %.2f |\n| L_surf gradient | %.2f |\n| L_surf Hessian (PSD-projected) | %.2f |\n",
              value_ms, gradient_ms, hessian_ms);
  std::printf("| CHOLMOD analysis + factorization | %.2f |\n| CHOLMOD factorization (analysis reused) | %.2f |\n",
              first_factor_ms, factor_ms);
  std::printf("| CHOLMOD solve | %.2f |\n", solve_ms);
  std::printf("symbolic analyses: %d\n", solver.analysis_count());
  return 0;
}
