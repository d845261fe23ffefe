#pragma once

#include <array>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/mesh/simulation_mesh.hpp"

namespace gr {

/// What the split of non-manifold edges did (report.json `split_non_manifold_edges`).
struct NonManifoldReport {
  int edges = 0;          ///< garment edges of more than two faces, split for the solver
  int vertex_copies = 0;  ///< vertex copies the split made (welded back in the written file)
};

/// The surface energy pairs the two faces of each edge, so the solver needs an
/// edge-manifold surface: an edge shared by more than two faces is split. Beyond its first
/// two faces (in face order), each of its faces takes copies of the edge's two vertices,
/// appended at the same positions; the copies are tied to their originals, and the document
/// still names the originals, so the written file welds them back.
/// @param ties gets the (copy, original) pairs.
NonManifoldReport split_non_manifold_edges(SimulationMesh& sim,
                                           std::vector<std::array<int, 2>>& ties);

nlohmann::json to_json(const NonManifoldReport& report);

}  // namespace gr
