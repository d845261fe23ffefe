#include <catch2/catch.hpp>

#include "core/common/errors.hpp"
#include "stage_chain.hpp"

namespace gr {

TEST_CASE("infer stage: without a source body the fit is tight, warned - ease needs the body",
          "[pipeline][stages]") {
  test::StageChain chain("infer");
  const InferOutput& out = chain.infer();
  CHECK(out.ease.fit == FitMode::kTight);
  CHECK_FALSE(out.ease.source_known);
  CHECK(out.source_ease.distance.empty());
  CHECK(out.skin_weights.size() == 0);  // levelset: no binding
  REQUIRE(chain.progress.warnings().size() == 1);
  CHECK_THAT(chain.progress.warnings().front(), Catch::Contains("no --source-body"));

  InferOptions ease;
  ease.fit_mode = FitMode::kEase;
  ease.out_dir = chain.out_dir.string();
  Progress progress(true);
  CHECK_THROWS_AS(run_infer({chain.read().scene, chain.prepare().normalized, chain.paths,
                             ShrinkMode::kLevelset},
                            ease, progress),
                  InputError);
}

TEST_CASE("infer stage: the garment's ease on its source body widens the fit's band",
          "[pipeline][stages]") {
  test::StageChain chain("infer_ease");
  // The garment's own avatar as its source body: the ease is its distance to it.
  chain.paths.source_body = chain.paths.avatar;
  const InferOutput& out = chain.infer();
  CHECK(out.ease.source_known);
  CHECK(out.ease.fit == FitMode::kEase);
  CHECK(out.source_ease.distance.size() ==
        static_cast<std::size_t>(chain.prepare().normalized.garment.vertices.rows()));
  CHECK(out.ease.distance_band >= kDistanceBand);
  CHECK(out.ease.max_offset > 0.0);
  CHECK(out.ease.max_offset < out.ease.distance_band);
}

}  // namespace gr
