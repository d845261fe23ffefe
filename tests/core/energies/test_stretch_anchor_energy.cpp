#include <string>

#include <catch2/catch.hpp>

#include <Eigen/Dense>

#include "core/energies/anchor_energy.hpp"
#include "core/energies/energy_checks.hpp"
#include "core/energies/stretch_energy.hpp"
#include "core/test_shapes.hpp"

using namespace gr;

namespace {

/// Rest mesh and a deformed state for the finite-difference checks.
struct StretchCase {
  const char* name;
  TriangleMesh rest;
  MatrixX3d deformed;
};

StretchCase stretch_case(int which) {
  std::srand(11 + which);
  switch (which) {
    case 0: {  // a curved grid, moved, scaled by 0.7 (compressed) and jittered
      TriangleMesh grid = test::curved_grid(4);
      MatrixX3d V = 0.7 * grid.vertices + 0.03 * MatrixX3d::Random(grid.vertices.rows(), 3);
      V.rowwise() += Eigen::RowVector3d(0.2, -0.1, 0.3);
      return {"compressed grid", grid, V};
    }
    case 1: {  // a cylinder stretched to 1.4 times along its axis
      TriangleMesh cylinder = open_cylinder(0.3, -0.5, 0.5, 3, 6);
      MatrixX3d V = cylinder.vertices;
      V.col(2) *= 1.4;
      V += 0.02 * MatrixX3d::Random(V.rows(), 3);
      return {"stretched cylinder", cylinder, V};
    }
    default: {  // one edge crushed to 1e-3 of its rest length, next to a sliver triangle
      TriangleMesh mesh;
      mesh.vertices.resize(4, 3);
      mesh.vertices << 0, 0, 0, 1, 0, 0, 0.5, 1e-3, 0, 0.4, 1, 0.2;
      mesh.faces.resize(2, 3);
      mesh.faces << 0, 1, 2, 0, 2, 3;
      MatrixX3d V = mesh.vertices;
      V.row(1) << 1e-3, 2e-4, -1e-4;
      V.row(3) += Eigen::RowVector3d(0.1, -0.2, 0.05);
      return {"near-degenerate", mesh, V};
    }
  }
}

}  // namespace

TEST_CASE("stretch energy: zero under rigid motion, derivatives match finite differences",
          "[energies][stretch][grad][hess]") {
  const StretchCase c = stretch_case(GENERATE(0, 1, 2));
  INFO(c.name);
  const int n = static_cast<int>(c.rest.vertices.rows());
  const DofLayout layout{n, false};
  const StretchEnergy energy(c.rest, layout);
  REQUIRE(!energy.elements().empty());

  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.7, Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  MatrixX3d moved = c.rest.vertices * R.transpose();
  moved.rowwise() += Eigen::RowVector3d(1, -2, 0.5);
  CHECK(energy.value(moved, 1.0) == Approx(0.0).margin(1e-20));

  test::check_position_energy(energy, test::flatten(c.deformed), 1e-5);
}

TEST_CASE("stretch energy: each edge's derivatives match finite differences",
          "[energies][stretch][grad][hess]") {
  const StretchCase c = stretch_case(GENERATE(0, 1, 2));
  INFO(c.name);
  const StretchEnergy energy(c.rest, DofLayout{static_cast<int>(c.rest.vertices.rows()), false});
  for (const StretchEnergy::Element& element : energy.elements()) {
    CAPTURE(element.vertices[0], element.vertices[1]);
    test::check_element_derivatives<StretchEnergy>(
        element, StretchEnergy::gather(element, c.deformed, 1.0), 1e-5);
  }
}

TEST_CASE("stretch energy: resists uniform scaling, strain integrated over the rest area",
          "[energies][stretch]") {
  const TriangleMesh grid = test::curved_grid(6);
  const StretchEnergy energy(grid, DofLayout{static_cast<int>(grid.vertices.rows()), false});
  // Uniform scaling by s: every edge's strain is s - 1, so the energy is (s - 1)^2 times
  // the sum of the edge areas, which is the total rest area.
  double area = 0.0;
  for (int f = 0; f < grid.faces.rows(); ++f) {
    const Vector3d a = grid.vertices.row(grid.faces(f, 0)), b = grid.vertices.row(grid.faces(f, 1)),
                   c = grid.vertices.row(grid.faces(f, 2));
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  CHECK(energy.value(0.8 * grid.vertices, 1.0) == Approx(0.04 * area).epsilon(1e-12));
  CHECK(energy.value(1.1 * grid.vertices, 1.0) == Approx(0.01 * area).epsilon(1e-12));
}

TEST_CASE("stretch energy: duplicate vertices give no element, a collapsed edge no NaN",
          "[energies][stretch]") {
  TriangleMesh mesh;
  mesh.vertices.resize(4, 3);
  mesh.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 0, 0;  // vertex 3 duplicates vertex 1
  mesh.faces.resize(2, 3);
  mesh.faces << 0, 1, 2, 1, 3, 2;  // the second face has zero area
  const DofLayout layout{4, false};
  const StretchEnergy energy(mesh, layout);
  // Edges 0-1, 1-2, 2-0 of the first face; 1-3 has no length and 3-2 no area.
  CHECK(energy.elements().size() == 3);
  MatrixX3d V = mesh.vertices;
  V.row(2) = V.row(0);  // edge 0-2 collapsed to a point
  Eigen::VectorXd g;
  energy.gradient(V, 1.0, g);
  CHECK(g.allFinite());
  CHECK(Eigen::MatrixXd(energy.hessian(V, 1.0, true)).allFinite());
  CHECK(energy.value(V, 1.0) > 0.0);
}

TEST_CASE("anchor energy: zero at rest, derivatives match finite differences",
          "[energies][anchor][grad][hess]") {
  const bool t_free = GENERATE(false, true);
  const TriangleMesh cylinder = open_cylinder(0.3, -0.5, 0.5, 3, 8);
  const int n = static_cast<int>(cylinder.vertices.rows());
  const std::vector<int> loop_vertices = boundary_loop_vertices(cylinder.faces);
  CHECK(loop_vertices.size() == 16);
  const DofLayout layout{n, t_free, 1.0};
  const AnchorEnergy energy(cylinder.vertices, loop_vertices, layout);
  CHECK(energy.value(cylinder.vertices, 1.0) == 0.0);

  std::srand(3);
  const MatrixX3d V = cylinder.vertices + 0.1 * MatrixX3d::Random(n, 3);
  double expected = 0.0;
  for (int v : loop_vertices) expected += 0.5 * (V.row(v) - cylinder.vertices.row(v)).squaredNorm();
  CHECK(energy.value(V, 1.0) == Approx(expected).epsilon(1e-14));
  if (!t_free) {
    test::check_position_energy(energy, test::flatten(V), 1e-6);
  } else {
    Eigen::VectorXd g;
    energy.gradient(V, 0.3, g);
    REQUIRE(g.size() == layout.dof_count());
    CHECK(g[layout.t_index()] == 0.0);
  }
}

TEST_CASE("anchor energy: each vertex's derivatives match finite differences",
          "[energies][anchor][grad][hess]") {
  const TriangleMesh grid = test::curved_grid(3);
  const int n = static_cast<int>(grid.vertices.rows());
  const std::vector<double> shares = vertex_area_shares(grid.vertices, grid.faces);
  const AnchorEnergy energy(grid.vertices, {0, 4, 8, 4}, DofLayout{n, false},
                            {shares[0], shares[4], shares[8], 0.0});
  std::srand(9);
  const MatrixX3d V = grid.vertices + 0.1 * MatrixX3d::Random(n, 3);
  for (const AnchorEnergy::Element& element : energy.elements()) {
    CAPTURE(element.vertex, element.weight);
    test::check_element_derivatives<AnchorEnergy>(element, AnchorEnergy::gather(element, V, 1.0),
                                                  1e-6);
  }
}

TEST_CASE("anchor energy: a vertex id outside the garment is rejected", "[energies][anchor]") {
  const TriangleMesh grid = test::curved_grid(3);
  const DofLayout layout{static_cast<int>(grid.vertices.rows()), false};
  CHECK_THROWS_AS(AnchorEnergy(grid.vertices, {0, static_cast<int>(grid.vertices.rows())}, layout),
                  std::invalid_argument);
}

TEST_CASE("anchor energy with weights (the tether): derivatives match finite differences",
          "[energies][anchor][grad][hess]") {
  const TriangleMesh grid = test::curved_grid(4);
  const int n = static_cast<int>(grid.vertices.rows());
  const std::vector<double> shares = vertex_area_shares(grid.vertices, grid.faces);
  double total = 0.0;
  for (Eigen::Index f = 0; f < grid.faces.rows(); ++f) {
    const Vector3d a = grid.vertices.row(grid.faces(f, 0)).transpose();
    total += 0.5 * (grid.vertices.row(grid.faces(f, 1)).transpose() - a)
                       .cross(grid.vertices.row(grid.faces(f, 2)).transpose() - a)
                       .norm();
  }
  double share_sum = 0.0;
  for (double s : shares) share_sum += s;
  CHECK(share_sum == Approx(total).epsilon(1e-12));

  std::vector<int> all(static_cast<std::size_t>(n));
  for (int v = 0; v < n; ++v) all[static_cast<std::size_t>(v)] = v;
  const DofLayout layout{n, false, 1.0};
  const AnchorEnergy tether(grid.vertices, all, layout, shares, "tether");
  CHECK(std::string(tether.name()) == "tether");
  std::srand(5);
  const MatrixX3d V = grid.vertices + 0.1 * MatrixX3d::Random(n, 3);
  double expected = 0.0;
  for (int v = 0; v < n; ++v)
    expected +=
        0.5 * shares[static_cast<std::size_t>(v)] * (V.row(v) - grid.vertices.row(v)).squaredNorm();
  CHECK(tether.value(V, 1.0) == Approx(expected).epsilon(1e-14));
  test::check_position_energy(tether, test::flatten(V), 1e-6);

  CHECK_THROWS_AS(AnchorEnergy(grid.vertices, {0, 1}, layout, {1.0}), std::invalid_argument);
  CHECK_THROWS_AS(AnchorEnergy(grid.vertices, {0}, layout, {-1.0}), std::invalid_argument);
}
