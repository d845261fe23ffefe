#include <set>
#include <string>

#include <catch2/catch.hpp>

#include "stage_chain.hpp"
#include "validate/checks/mesh_intersections.hpp"

namespace gr {

TEST_CASE("inflate stage: the avatar grows back to t = 1 with the garment clear of it",
          "[pipeline][stages]") {
  test::StageChain chain("inflate");
  const InflateOutput& out = chain.inflate();
  INFO(out.inflation.message);
  REQUIRE(out.inflation.succeeded());
  CHECK(out.inflation.t == 1.0);
  CHECK(out.report.status == "snapped");
  CHECK(out.report.al_rounds >= 1);
  CHECK(out.report.newton_iterations > 0);
  const NormalizedScene& scene = chain.prepare().normalized;
  const TriangleMesh garment{out.inflation.garment, scene.garment.faces};
  CHECK(find_intersecting_face_pairs(garment, scene.avatar).count == 0);

  // Frames: the start, then one per round.
  test::StageChain framed("inflate_frames");
  std::set<std::string> names;
  const FrameWriter record = [&](const std::string& name, const MatrixX3d& garment_frame,
                                 const MatrixX3d& avatar_frame) {
    CHECK(garment_frame.rows() == scene.garment.vertices.rows());
    CHECK(avatar_frame.rows() == scene.avatar.vertices.rows());
    names.insert(name);
  };
  const InflateOutput again =
      run_inflate({framed.solver()}, {framed.parameters.solver, record, {}}, framed.progress);
  CHECK(names.count("round_00") == 1);
  CHECK(names.size() == static_cast<std::size_t>(again.report.al_rounds) + 1);

  InflateReport total = out.report;
  add_inflation_attempt(total, again.report);
  CHECK(total.al_rounds == out.report.al_rounds + again.report.al_rounds);
  CHECK(total.newton_iterations == out.report.newton_iterations + again.report.newton_iterations);
}

}  // namespace gr
