#include <catch2/catch.hpp>

#include "stage_chain.hpp"
#include "validate/checks/mesh_intersections.hpp"

namespace gr {

TEST_CASE("fit stage: the garment settles clear of the avatar, with its terms reported",
          "[pipeline][stages]") {
  test::StageChain chain("fit");
  const FitOutput& out = chain.fit();
  INFO(out.fit.solve.message);
  CHECK(out.report.status == "converged");
  CHECK(out.report.newton_iterations > 0);
  CHECK(out.report.energies.count("surface") == 1);
  CHECK(out.report.energies.count("fit") == 1);
  CHECK(out.report.surface_energy_per_area >= 0.0);
  CHECK(out.report.min_distance > 0.0);
  CHECK_FALSE(out.ease_targets);  // tight: no source ease given
  const NormalizedScene& scene = chain.prepare().normalized;
  const TriangleMesh garment{out.fit.garment, scene.garment.faces};
  CHECK(find_intersecting_face_pairs(garment, scene.avatar).count == 0);
}

}  // namespace gr
