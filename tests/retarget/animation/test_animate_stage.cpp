#include <filesystem>
#include <string>

#include <catch2/catch.hpp>

#include "core/io/gltf_document.hpp"
#include "retarget/gltf_scene.hpp"
#include "retarget/stages/animate_stage.hpp"
#include "scenes/synthetic/bending_arm.hpp"
#include "test_support.hpp"

namespace gr {
namespace {

TEST_CASE("a sleeve on a bending elbow: skinning crosses the arm, the corrected frames do not",
          "[animation]") {
  const auto dir = test::fresh_temp_dir("animate_bending_elbow");
  write_bending_arm_scene(make_bending_arm_scene(45.0), dir.string());
  const std::string sleeve = (dir / "sleeve.glb").string();
  const std::string arm = (dir / "arm.glb").string();
  const MatrixX3d rest = read_gltf(sleeve).document.positions;

  Progress progress(true);
  const std::vector<std::string> files{sleeve};
  const std::vector<std::string> meshes{""};
  const std::vector<std::string> avatar_meshes;
  AnimateOptions options;
  options.clips = {"bend"};
  const AnimateOutput output = run_animate({files, meshes, arm, avatar_meshes}, options, progress);
  REQUIRE(output.clips.size() == 1);
  const AnimationReport& clip = output.clips.front();
  INFO(clip_summary(clip.skinned) << "\n" << clip_summary(clip.written));
  CHECK(clip.skinned.frames.size() == 31);
  CHECK(clip.skinned.crossing_frames() > 5);
  CHECK(clip.corrected_frames == static_cast<int>(clip.skinned.crossing_frames()));
  // A frame plays a solved correction or the last one carried on, one target per solve.
  CHECK(clip.solved_frames >= 1);
  CHECK(clip.solved_frames + clip.carried_frames == clip.corrected_frames);
  CHECK(clip.morph_targets == clip.solved_frames);
  CHECK(clip.corrections_failed == 0);
  // Each settling stops at its cap.
  CHECK(clip.settle_iterations <= options.parameters.settle_max_iterations * clip.solves);
  // Every frame of the file as written, played with its morph weights, is free.
  CHECK(clip.written.crossing_frames() == 0);
  CHECK(output.certified());

  // The rest pose is what it was, and the file carries the clip and one target a solve.
  const GltfAsset written = read_gltf(sleeve);
  CHECK(written.document.positions == rest);
  const std::vector<AnimationClip> clips = read_gltf_animations(sleeve);
  REQUIRE(clips.size() == 1);
  CHECK(clips.front().name == "bend");
  bool weights = false;
  for (const AnimationChannel& channel : clips.front().channels)
    if (channel.path == ChannelPath::kWeights) {
      weights = true;
      CHECK(channel.values.cols() == clip.morph_targets);
      CHECK(channel.times.size() == 31);
    }
  CHECK(weights);
  const std::vector<MeshMorphTargets> targets =
      read_morph_targets(written.gltf, sleeve, written.document.positions.rows());
  REQUIRE(targets.size() == 1);
  CHECK(static_cast<int>(targets.front().deltas.size()) == clip.morph_targets);
  // A valid glTF file, as the Khronos validator reads it.
  const test::ValidatorRun validator = test::run_gltf_validator(sleeve);
  INFO(validator.summary.dump(2));
  CHECK(validator.exit_code == 0);
  CHECK(validator.summary["errors"] == 0);
}

TEST_CASE("a settling cut to one Newton step still leaves every frame of the clip free",
          "[animation]") {
  const auto dir = test::fresh_temp_dir("animate_short_settle");
  write_bending_arm_scene(make_bending_arm_scene(45.0), dir.string());
  const std::vector<std::string> files{(dir / "sleeve.glb").string()};
  const std::vector<std::string> meshes{""};
  const std::vector<std::string> avatar_meshes;
  Progress progress(true);
  AnimateOptions options;
  options.clips = {"bend"};
  options.parameters.settle_max_iterations = 1;
  const AnimateOutput output =
      run_animate({files, meshes, (dir / "arm.glb").string(), avatar_meshes}, options, progress);
  REQUIRE(output.clips.size() == 1);
  const AnimationReport& clip = output.clips.front();
  INFO(clip_summary(clip.skinned) << "\n" << clip_summary(clip.written));
  CHECK(clip.solves >= 1);
  CHECK(clip.settle_iterations <= clip.solves);
  CHECK(clip.corrections_failed == 0);
  CHECK(clip.written.crossing_frames() == 0);
  CHECK(output.certified());
}

}  // namespace
}  // namespace gr
