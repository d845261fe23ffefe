#include "garment/repairs/non_manifold_edges.hpp"

#include <algorithm>
#include <map>
#include <utility>

namespace gr {

NonManifoldReport split_non_manifold_edges(SimulationMesh& sim,
                                           std::vector<std::array<int, 2>>& ties) {
  auto& F = sim.mesh.faces;
  std::map<std::pair<int, int>, std::vector<int>> faces_of_edge;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      faces_of_edge[{std::min(a, b), std::max(a, b)}].push_back(static_cast<int>(f));
    }
  std::map<std::pair<int, int>, int> copy_of;  // (face, original) -> copy
  std::vector<Vector3d> copies;
  NonManifoldReport report;
  for (const auto& [edge, faces] : faces_of_edge) {
    if (faces.size() <= 2) continue;
    ++report.edges;
    for (std::size_t i = 2; i < faces.size(); ++i)
      for (const int original : {edge.first, edge.second}) {
        const int f = faces[i];
        auto [it, added] = copy_of.emplace(std::pair{f, original}, 0);
        if (added) {
          it->second = static_cast<int>(sim.mesh.vertices.rows() + copies.size());
          copies.push_back(sim.mesh.vertices.row(original).transpose());
          sim.sim_to_obj.push_back(sim.sim_to_obj[static_cast<std::size_t>(original)]);
          ties.push_back({it->second, original});
        }
        for (int k = 0; k < 3; ++k)
          if (F(f, k) == original) F(f, k) = it->second;
      }
  }
  const Eigen::Index old_count = sim.mesh.vertices.rows();
  sim.mesh.vertices.conservativeResize(old_count + static_cast<Eigen::Index>(copies.size()), 3);
  for (std::size_t c = 0; c < copies.size(); ++c)
    sim.mesh.vertices.row(old_count + static_cast<Eigen::Index>(c)) = copies[c].transpose();
  report.vertex_copies = static_cast<int>(copies.size());
  return report;
}

nlohmann::json to_json(const NonManifoldReport& report) {
  return {{"edges", report.edges},
          {"vertex_copies", report.vertex_copies},
          {"meaning",
           "edges shared by more than two faces: the faces beyond the first two took tied copies "
           "of the edge's vertices for the solver; the written file welds them back"}};
}

}  // namespace gr
