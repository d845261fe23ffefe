#include <catch2/catch.hpp>

#include "stage_chain.hpp"
#include "validate/checks/mesh_intersections.hpp"

namespace gr {

TEST_CASE("shrink stage: a shrunk avatar free of the garment, and the grid the fit reads",
          "[pipeline][stages]") {
  test::StageChain chain("shrink");
  const ShrinkOutput& out = chain.shrink();
  REQUIRE_FALSE(out.failure);
  const NormalizedScene& scene = chain.prepare().normalized;
  CHECK(out.shrunk.vertices.rows() == scene.avatar.vertices.rows());
  CHECK(out.report.mode == ShrinkMode::kLevelset);
  CHECK(out.report.depth > 0.0);
  CHECK(out.grid.active_voxel_count() > 0);
  CHECK(out.pierced_faces.empty());
  // Checked again here, exactly: the shrunk avatar against the garment.
  const TriangleMesh shrunk{out.shrunk.vertices, scene.avatar.faces};
  CHECK(find_intersecting_face_pairs(scene.garment, shrunk).count == 0);
}

}  // namespace gr
