#include <catch2/catch.hpp>

#include "core/mesh/primitives.hpp"
#include "retarget/scene/avatar_coverage.hpp"

namespace gr {
namespace {

/// Two bones up the z axis, 0→1 and 1→2, as both skeletons.
Skeleton two_bones() {
  Skeleton skeleton;
  skeleton.joints.resize(3, 3);
  skeleton.joints << 0, 0, 0, 0, 0, 1, 0, 0, 2;
  skeleton.bones.resize(2, 2);
  skeleton.bones << 0, 1, 1, 2;
  return skeleton;
}

NormalizedScene sleeve_on(const TriangleMesh& avatar) {
  NormalizedScene scene;
  scene.garment = open_cylinder(0.2, 0.05, 1.95, 20, 16);
  scene.avatar = avatar;
  scene.source_skeleton = two_bones();
  scene.target_skeleton = two_bones();
  return scene;
}

TEST_CASE("a sleeve over two bones on an arm that has only the first lacks the second's surface",
          "[coverage]") {
  SECTION("the arm has both bones") {
    const AvatarCoverage coverage =
        measure_avatar_coverage(sleeve_on(open_cylinder(0.1, 0.0, 2.0, 21, 12)));
    REQUIRE(coverage.garment_area.size() == 2);
    CHECK(coverage.garment_area[0] > 0.0);
    CHECK(coverage.garment_area[1] > 0.0);
    CHECK(coverage.avatar_area[1] > 0.0);
    CHECK(coverage.uncovered_bones.empty());
    CHECK(coverage.uncovered_share == 0.0);
  }
  SECTION("the arm is cut at the second joint") {
    const AvatarCoverage coverage =
        measure_avatar_coverage(sleeve_on(open_cylinder(0.1, 0.0, 0.95, 11, 12)));
    CHECK(coverage.avatar_area[1] == 0.0);
    REQUIRE(coverage.uncovered_bones == std::vector<int>{1});
    // The sleeve's upper half: its faces whose centroids lie above the second joint.
    CHECK(coverage.uncovered_share == Approx(0.5).margin(0.03));
  }
  SECTION("a stub of the second bone's surface, less than a twentieth of the sleeve's there") {
    TriangleMesh arm = open_cylinder(0.1, 0.0, 1.05, 12, 12);
    const AvatarCoverage coverage = measure_avatar_coverage(sleeve_on(arm));
    CHECK(coverage.avatar_area[1] > 0.0);
    CHECK(coverage.avatar_area[1] < kMinAvatarToGarmentArea * coverage.garment_area[1]);
    CHECK(coverage.uncovered_bones == std::vector<int>{1});
  }
  SECTION("without skeletons, nothing is measured") {
    NormalizedScene scene = sleeve_on(open_cylinder(0.1, 0.0, 0.95, 11, 12));
    scene.target_skeleton.reset();
    const AvatarCoverage coverage = measure_avatar_coverage(scene);
    CHECK(coverage.garment_area.empty());
    CHECK(coverage.uncovered_share == 0.0);
  }
}

TEST_CASE("bones are named by their joints, or by their index without names", "[coverage]") {
  const Skeleton skeleton = two_bones();
  CHECK(bone_name(skeleton, {"Arm", "ForeArm", "Hand"}, 1) == "ForeArm-Hand");
  CHECK(bone_name(skeleton, {}, 1) == "bone 1");
}

}  // namespace
}  // namespace gr
