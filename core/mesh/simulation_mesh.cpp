#include "core/mesh/simulation_mesh.hpp"

#include <array>
#include <map>

namespace gr {

SimulationMesh make_simulation_mesh(const ObjDocument& doc) {
  SimulationMesh sim;
  const auto positions = static_cast<std::size_t>(doc.positions.rows());
  std::vector<bool> referenced(positions, false);
  for (const auto& face : doc.faces)
    for (const auto& corner : face) referenced[static_cast<std::size_t>(corner.position)] = true;

  sim.obj_to_sim.assign(positions, -1);
  std::map<std::array<double, 3>, int> welded;
  for (std::size_t i = 0; i < positions; ++i) {
    if (!referenced[i]) continue;
    const auto row = static_cast<Eigen::Index>(i);
    const std::array<double, 3> key{doc.positions(row, 0), doc.positions(row, 1),
                                    doc.positions(row, 2)};
    auto [it, inserted] = welded.emplace(key, static_cast<int>(sim.sim_to_obj.size()));
    if (inserted) sim.sim_to_obj.push_back(static_cast<int>(i));
    sim.obj_to_sim[i] = it->second;
  }

  sim.mesh.vertices.resize(static_cast<Eigen::Index>(sim.sim_to_obj.size()), 3);
  for (std::size_t s = 0; s < sim.sim_to_obj.size(); ++s)
    sim.mesh.vertices.row(static_cast<Eigen::Index>(s)) = doc.positions.row(sim.sim_to_obj[s]);

  std::vector<std::array<int, 3>> faces;
  for (std::size_t f = 0; f < doc.faces.size(); ++f) {
    std::array<int, 3> tri{};
    for (int k = 0; k < 3; ++k)
      tri[static_cast<std::size_t>(k)] = sim.obj_to_sim[static_cast<std::size_t>(
          doc.faces[f][static_cast<std::size_t>(k)].position)];
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) {
      ++sim.collapsed_faces;
      continue;
    }
    faces.push_back(tri);
    sim.face_to_obj.push_back(static_cast<int>(f));
  }
  sim.mesh.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (int k = 0; k < 3; ++k)
      sim.mesh.faces(static_cast<Eigen::Index>(f), k) = faces[f][static_cast<std::size_t>(k)];
  return sim;
}

}  // namespace gr
