#include <catch2/catch.hpp>

#include <array>
#include <vector>

#include "garment/repairs/non_manifold_edges.hpp"

namespace gr {

namespace {

/// Three triangles fanned around the edge (0, 1), and a fourth beside the first.
SimulationMesh fan_of_three() {
  SimulationMesh sim;
  sim.mesh.vertices.resize(6, 3);
  sim.mesh.vertices << 0, 0, 0, 1, 0, 0, 0.5, 1, 0, 0.5, -1, 0, 0.5, 0, 1, 1.5, 1, 0;
  sim.mesh.faces.resize(4, 3);
  sim.mesh.faces << 0, 1, 2, 1, 0, 3, 0, 1, 4, 1, 5, 2;
  for (int v = 0; v < 6; ++v) sim.sim_to_obj.push_back(v);
  return sim;
}

}  // namespace

TEST_CASE("non-manifold edges: the third face of an edge takes tied copies of its vertices",
          "[repairs]") {
  SimulationMesh sim = fan_of_three();
  std::vector<std::array<int, 2>> ties;
  const NonManifoldReport report = split_non_manifold_edges(sim, ties);
  CHECK(report.edges == 1);
  CHECK(report.vertex_copies == 2);
  REQUIRE(sim.mesh.vertices.rows() == 8);
  REQUIRE(ties.size() == 2);
  for (const auto& [copy, original] : ties) {
    CHECK(copy >= 6);
    CHECK(sim.mesh.vertices.row(copy) == sim.mesh.vertices.row(original));
    CHECK(sim.sim_to_obj[static_cast<std::size_t>(copy)] == original);
  }
  // The first two faces keep the edge; the third now uses the copies.
  CHECK(sim.mesh.faces.row(0) == Eigen::RowVector3i(0, 1, 2));
  CHECK(sim.mesh.faces.row(1) == Eigen::RowVector3i(1, 0, 3));
  CHECK(sim.mesh.faces(2, 0) >= 6);
  CHECK(sim.mesh.faces(2, 1) >= 6);
  CHECK(sim.mesh.faces(2, 2) == 4);
  const nlohmann::json section = to_json(report);
  CHECK(section["edges"] == 1);
  CHECK(section["vertex_copies"] == 2);
}

TEST_CASE("non-manifold edges: a manifold surface is left as it is", "[repairs]") {
  SimulationMesh sim = fan_of_three();
  sim.mesh.faces.conservativeResize(2, 3);
  const SimulationMesh before = sim;
  std::vector<std::array<int, 2>> ties;
  const NonManifoldReport report = split_non_manifold_edges(sim, ties);
  CHECK(report.edges == 0);
  CHECK(report.vertex_copies == 0);
  CHECK(ties.empty());
  CHECK(sim.mesh.vertices == before.mesh.vertices);
  CHECK(sim.mesh.faces == before.mesh.faces);
}

}  // namespace gr
