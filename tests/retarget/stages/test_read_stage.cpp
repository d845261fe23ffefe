#include <catch2/catch.hpp>

#include "core/common/errors.hpp"
#include "stage_chain.hpp"

namespace gr {

TEST_CASE("read stage: the scene, its memory estimate and the shrink mode", "[pipeline][stages]") {
  test::StageChain chain("read");
  const ReadOutput& read = chain.read();
  CHECK(read.scene.garment.mesh.faces.rows() > 0);
  CHECK(read.scene.avatar.mesh.faces.rows() > 0);
  CHECK(read.shrink_mode == ShrinkMode::kLevelset);  // no skeletons
  CHECK(read.estimated_memory_mb > 0.0);

  Progress progress(true);
  CHECK_THROWS_AS(run_read({chain.paths}, {RunLimits{}, ShrinkMode::kSkeleton}, progress),
                  InputError);
  RunLimits few_faces;
  few_faces.max_faces = 10;
  CHECK_THROWS_AS(run_read({chain.paths}, {few_faces, {}}, progress), InputError);
  ScenePaths missing = chain.paths;
  missing.garment += ".missing";
  CHECK_THROWS_AS(run_read({missing}, {}, progress), InputError);
  CHECK(progress.warnings().empty());
}

}  // namespace gr
