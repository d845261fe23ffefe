#include <catch2/catch.hpp>

#include "stage_chain.hpp"

namespace gr {

TEST_CASE("prepare stage: normalized scene, lattice below the barrier, nothing to repair",
          "[pipeline][stages]") {
  test::StageChain chain("prepare");
  const PrepareOutput& out = chain.prepare();
  const NormalizedScene& scene = out.normalized;
  // Every row of the scene as read, in normalized units (the body about 2 across).
  CHECK(scene.garment.vertices.rows() == chain.read().scene.garment.mesh.vertices.rows());
  const double extent =
      (scene.avatar.vertices.colwise().maxCoeff() - scene.avatar.vertices.colwise().minCoeff())
          .maxCoeff();
  CHECK(extent == Approx(2.0).epsilon(0.05));
  CHECK(out.report.lattice > 0.0);
  CHECK(out.report.lattice < chain.parameters.solver.dhat);
  CHECK(out.ccd_min_separation >= out.report.lattice);
  CHECK(out.repairs.crossings.pairs == 0);
  CHECK(out.repairs.non_manifold.edges == 0);
  CHECK(out.pierced.pairs.empty());
  CHECK(out.inherited.pairs.empty());
  CHECK(out.report.garment_faces == scene.garment.faces.rows());
  CHECK(chain.progress.warnings().empty());
}

}  // namespace gr
