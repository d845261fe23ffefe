#pragma once

#include <vector>

#include "core/common/types.hpp"
#include "core/io/obj_document.hpp"

namespace gr {

/// The welded position mesh the solver sees, with the maps back to the OBJ document.
struct SimulationMesh {
  TriangleMesh mesh;             ///< welded vertices (#V×3) and non-degenerate faces (#F×3)
  std::vector<int> obj_to_sim;   ///< per OBJ position: welded vertex, or -1 when unreferenced
  std::vector<int> sim_to_obj;   ///< per welded vertex: first OBJ position that maps to it
  std::vector<int> face_to_obj;  ///< per simulation face: its face in the OBJ document
  int collapsed_faces = 0;       ///< faces dropped because two corners welded together
};

/// Welds positions that are bit-identical (UV seams written as duplicate `v` lines) and
/// keeps only vertices some face references. A face whose corners weld together is not
/// simulated (counted in collapsed_faces) but stays in the document for export.
SimulationMesh make_simulation_mesh(const ObjDocument& document);

/// OBJ positions (#P×3) for export: welded vertices take `sim_vertices` (#V×3); positions
/// no face references are mapped by `map_unreferenced` (for example the change of frame).
template <typename MapPoint>
MatrixX3d export_positions(const ObjDocument& document, const SimulationMesh& sim,
                           const Eigen::Ref<const MatrixX3d>& sim_vertices,
                           MapPoint map_unreferenced) {
  MatrixX3d out(document.positions.rows(), 3);
  for (Eigen::Index i = 0; i < out.rows(); ++i) {
    const int s = sim.obj_to_sim[static_cast<std::size_t>(i)];
    if (s >= 0)
      out.row(i) = sim_vertices.row(s);
    else
      out.row(i) = map_unreferenced(Vector3d(document.positions.row(i).transpose())).transpose();
  }
  return out;
}

}  // namespace gr
