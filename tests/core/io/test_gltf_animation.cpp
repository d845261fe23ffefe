#include <cmath>
#include <string>

#include <catch2/catch.hpp>

#include "core/common/errors.hpp"
#include "core/io/gltf_animation.hpp"
#include "gltf_fixture.hpp"
#include "scenes/synthetic/bending_arm.hpp"
#include "test_support.hpp"

namespace gr {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// The angle of a rotation about +z given as (x, y, z, w), in degrees.
double z_angle_degrees(const Eigen::VectorXd& q) {
  return 2.0 * std::atan2(q(2), q(3)) * 180.0 / kPi;
}

TEST_CASE("an animation written into a GLB reads back with its channel and span",
          "[gltf][animation]") {
  const auto dir = test::fresh_temp_dir("gltf_animation_round_trip");
  const BendingArmScene scene = make_bending_arm_scene(90.0);
  write_bending_arm_scene(scene, dir.string());
  const std::vector<AnimationClip> clips = read_gltf_animations((dir / "arm.glb").string());
  REQUIRE(clips.size() == 1);
  const AnimationClip& clip = clips.front();
  CHECK(clip.name == "bend");
  CHECK(clip.start == 0.0);
  CHECK(clip.end == Approx(1.0));
  REQUIRE(clip.channels.size() == 1);
  const AnimationChannel& elbow = clip.channels.front();
  CHECK(elbow.node == "elbow");
  CHECK(elbow.path == ChannelPath::kRotation);
  CHECK(elbow.interpolation == KeyInterpolation::kLinear);
  REQUIRE(elbow.values.rows() == 3);
  CHECK(z_angle_degrees(sample_channel(elbow, 1.0)) == Approx(90.0).margin(1e-4));
  // Spherical interpolation turns at a constant rate between the keys.
  CHECK(z_angle_degrees(sample_channel(elbow, 0.25)) == Approx(22.5).margin(1e-4));
  CHECK(z_angle_degrees(sample_channel(elbow, -3.0)) == Approx(0.0).margin(1e-6));
  CHECK(z_angle_degrees(sample_channel(elbow, 7.0)) == Approx(90.0).margin(1e-4));
  // The file without clips has none.
  CHECK(read_gltf_animations((dir / "sleeve.glb").string()).empty());
}

TEST_CASE("step and cubic spline channels interpolate as glTF defines", "[animation]") {
  AnimationChannel step;
  step.path = ChannelPath::kTranslation;
  step.interpolation = KeyInterpolation::kStep;
  step.times = {0.0, 1.0};
  step.values.resize(2, 3);
  step.values << 0, 0, 0, 2, 4, 6;
  CHECK(sample_channel(step, 0.99)(0) == 0.0);
  CHECK(sample_channel(step, 1.0)(1) == 4.0);

  // A cubic spline with zero tangents eases in and out: at the middle, the middle value.
  AnimationChannel cubic = step;
  cubic.interpolation = KeyInterpolation::kCubicSpline;
  cubic.values.resize(6, 3);
  cubic.values << 0, 0, 0, 0, 0, 0, 0, 0, 0,  //
      0, 0, 0, 2, 4, 6, 0, 0, 0;
  CHECK(sample_channel(cubic, 0.5)(0) == Approx(1.0));
  CHECK(sample_channel(cubic, 0.25)(0) == Approx(2.0 * (3 * 0.0625 - 2 * 0.015625)));
  // With an out-tangent, the curve leaves the first key at that slope.
  cubic.values.row(2) << 8, 0, 0;
  const double h = 1e-6;
  CHECK(sample_channel(cubic, h)(0) / h == Approx(8.0).epsilon(1e-4));
}

TEST_CASE("a channel whose times run backwards is refused with the file named",
          "[gltf][animation]") {
  const auto dir = test::fresh_temp_dir("gltf_animation_backwards");
  write_bending_arm_scene(make_bending_arm_scene(), dir.string());
  tinygltf::Model model = test::load_glb((dir / "arm.glb").string());
  const int input = model.animations.at(0).samplers.at(0).input;
  const tinygltf::Accessor& accessor = model.accessors.at(static_cast<std::size_t>(input));
  const tinygltf::BufferView& view =
      model.bufferViews.at(static_cast<std::size_t>(accessor.bufferView));
  auto* times = reinterpret_cast<float*>(model.buffers[0].data.data() + view.byteOffset +
                                         accessor.byteOffset);
  times[1] = 2.0f;  // 0, 2, 1
  const std::string broken = (dir / "broken.glb").string();
  test::save_model(model, broken, true);
  try {
    read_gltf_animations(broken);
    FAIL("read a clip with backwards times");
  } catch (const InputError& error) {
    CHECK_THAT(error.what(), Catch::Contains("broken.glb"));
    CHECK_THAT(error.what(), Catch::Contains("strictly increasing"));
  }
}

}  // namespace
}  // namespace gr
