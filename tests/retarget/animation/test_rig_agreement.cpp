#include <cmath>
#include <string>

#include <catch2/catch.hpp>

#include "core/io/gltf_fixture.hpp"
#include "retarget/animation/animation_check.hpp"
#include "scenes/synthetic/bending_arm.hpp"
#include "test_support.hpp"

namespace gr {
namespace {

TEST_CASE("a garment whose rig a clip places otherwise than the avatar's is not certified",
          "[animation]") {
  const auto dir = test::fresh_temp_dir("rig_agreement");
  const BendingArmScene arm = make_bending_arm_scene(45.0);
  write_bending_arm_scene(arm, dir.string());
  const std::string avatar = (dir / "arm-armature.glb").string();
  const std::string kept = (dir / "sleeve-armature.glb").string();
  const std::string baked = (dir / "sleeve-baked.glb").string();
  test::put_under_armature((dir / "arm.glb").string(), avatar, false);
  test::put_under_armature((dir / "sleeve.glb").string(), kept, false);
  test::put_under_armature((dir / "sleeve.glb").string(), baked, true);

  // The clip bends the elbow and turns the shoulder, the root joint, about +z: set by the
  // clip, a root joint with the armature baked in loses the armature's turn and scale.
  AnimationClip clip = arm.bend;
  AnimationChannel turn;
  turn.node = arm.arm_skin.joints[0].name;
  turn.times = {clip.start, clip.end};
  turn.values.resize(2, 4);
  turn.values << 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, std::sin(0.2), std::cos(0.2);
  clip.channels.push_back(turn);
  const ChosenClip chosen{clip, ClipTranslations::kAll};

  const ClipFindings together =
      check_clip(read_animated_scene({kept}, {""}, avatar, {}), chosen, 30.0);
  CHECK(together.rigs_agree());
  CHECK(together.joint_drift < 1e-9);
  CHECK(to_json(together)["certified"] == together.certified());

  const ClipFindings apart =
      check_clip(read_animated_scene({baked}, {""}, avatar, {}), chosen, 30.0);
  CHECK_FALSE(apart.rigs_agree());
  CHECK_FALSE(apart.certified());
  CHECK(apart.joint_drift > 0.1);
  CHECK(to_json(apart)["certified"] == false);
  CHECK(to_json(apart)["joint_drift"]["largest"] == apart.joint_drift);
  CHECK(clip_summary(apart).find("place the rig otherwise") != std::string::npos);
}

}  // namespace
}  // namespace gr
