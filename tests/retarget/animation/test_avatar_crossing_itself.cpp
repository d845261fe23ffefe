#include <string>

#include <catch2/catch.hpp>

#include "retarget/animation/animation_check.hpp"
#include "scenes/synthetic/bending_arm.hpp"
#include "test_support.hpp"

namespace gr {
namespace {

/// The sleeve skinned on the synthetic arm bent by `degrees`, every frame checked.
ClipFindings bent_arm_findings(double degrees, const char* name) {
  const auto dir = test::fresh_temp_dir(name);
  write_bending_arm_scene(make_bending_arm_scene(degrees), dir.string());
  const std::string arm = (dir / "arm.glb").string();
  const AnimatedScene scene = read_animated_scene({(dir / "sleeve.glb").string()}, {""}, arm, {});
  return check_clip(scene, choose_clips({"bend"}, arm, 30.0).front(), 30.0);
}

TEST_CASE("a crossing frame says when the avatar's own skin crosses itself there", "[animation]") {
  // Bent by 30°, the arm's inner elbow stays open; the sleeve's stepped weights still make
  // it cross the arm.
  const ClipFindings open = bent_arm_findings(30.0, "avatar_self_open_elbow");
  REQUIRE(open.crossing_frames() > 0);
  CHECK(open.avatar_crossing_itself_frames() == 0);
  for (const FrameFindings& frame : open.frames) CHECK(frame.avatar_self_pairs == 0);

  // Bent by 120°, the inner elbow closes through itself in the last frames: those frames
  // say so, the first ones do not, and the count is no part of the frame's total.
  const ClipFindings closed = bent_arm_findings(120.0, "avatar_self_closed_elbow");
  CHECK(closed.avatar_crossing_itself_frames() > 0);
  CHECK(closed.frames.front().avatar_self_pairs == 0);
  CHECK(closed.frames.back().avatar_self_pairs > 0);
  CHECK(closed.frames.back().total() > 0);
  for (const FrameFindings& frame : closed.frames)
    if (frame.total() == 0) CHECK(frame.avatar_self_pairs == 0);
  CHECK(clip_summary(closed).find("the avatar crosses itself") != std::string::npos);
  CHECK(to_json(closed)["avatar_crossing_itself_frames"] == closed.avatar_crossing_itself_frames());
}

}  // namespace
}  // namespace gr
