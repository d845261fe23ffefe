#include <fstream>

#include <catch2/catch.hpp>

#include "core/common/errors.hpp"
#include "core/skeleton/skin_matching.hpp"
#include "test_support.hpp"

namespace gr {
namespace {

/// A chain of joints named `names`, each 1 above its parent (`parent[i]`).
SkinBinding chain(const std::vector<std::string>& names, const std::vector<int>& parent) {
  SkinBinding skin;
  for (std::size_t j = 0; j < names.size(); ++j) {
    SkinJoint joint;
    joint.name = names[j];
    joint.parent = parent[j];
    joint.world.setIdentity();
    joint.world(2, 3) = static_cast<double>(j);
    joint.inverse_bind = joint.world.inverse();
    skin.joints.push_back(joint);
  }
  return skin;
}

TEST_CASE("Skins match by name, through a joint map, and say which joints are missing",
          "[skeleton][skin]") {
  const SkinBinding source = chain({"hips", "spine", "neck", "head"}, {-1, 0, 1, 2});
  // The target names its joints otherwise, in another order, with one joint more.
  const SkinBinding target = chain({"Hips", "Spine", "Spine1", "Neck", "Head"}, {-1, 0, 1, 2, 3});

  SECTION("missing joints are listed") {
    REQUIRE_THROWS_WITH(match_skin_skeletons(source, target, {}, "avatar.glb"),
                        Catch::Contains("lacks 4 of the garment's skin joints") &&
                            Catch::Contains("'hips', 'spine', 'neck', 'head'"));
  }
  SECTION("a map matches them; the target's extra joint folds into its kept ancestor") {
    const JointMap map = {{"hips", "Hips"}, {"spine", "Spine"}, {"neck", "Neck"}, {"head", "Head"}};
    const MatchedSkeletons matched = match_skin_skeletons(source, target, map, "avatar.glb");
    REQUIRE(matched.target_joint == std::vector<int>{0, 1, 3, 4});
    REQUIRE(matched.source.bones.rows() == 3);
    REQUIRE(matched.source.bones == matched.target.bones);
    REQUIRE(matched.target.joints(2, 2) == 3.0);  // "Neck" sits at z = 3 in the target
    REQUIRE(matched.kept_joint_of_target == std::vector<int>{0, 1, 1, 2, 3});
  }
  SECTION("'-' leaves a source joint out; bones skip it") {
    const JointMap map = {{"hips", "Hips"}, {"spine", "-"}, {"neck", "Neck"}, {"head", "Head"}};
    const MatchedSkeletons matched = match_skin_skeletons(source, target, map, "avatar.glb");
    REQUIRE(matched.target_joint.size() == 3);
    REQUIRE(matched.source.bones.rows() == 2);
    REQUIRE(matched.source.bones(0, 0) == 0);  // hips -> neck
    REQUIRE(matched.source.bones(0, 1) == 1);
  }
}

TEST_CASE("The nearest-bone binding shares a point between its bone's joints", "[skeleton][skin]") {
  Skeleton skeleton;
  skeleton.joints.resize(3, 3);
  skeleton.joints << 0, 0, 0, 0, 0, 1, 1, 0, 1;  // up the z axis, then along x
  skeleton.bones.resize(2, 2);
  skeleton.bones << 0, 1, 1, 2;
  MatrixX3d points(3, 3);
  points << 0.1, 0, 0.25,  // beside the first bone, a quarter up
      0.75, 0.1, 1.2,      // above the second, three quarters along
      -1, 0, -1;           // below the first joint: clamped to it
  const Eigen::MatrixXd w = nearest_bone_weights(skeleton, points);
  REQUIRE(w.rows() == 3);
  REQUIRE(w.col(0).isApprox(Eigen::Vector3d(0.75, 0.25, 0.0)));
  REQUIRE(w.col(1).isApprox(Eigen::Vector3d(0.0, 0.25, 0.75)));
  REQUIRE(w.col(2).isApprox(Eigen::Vector3d(1.0, 0.0, 0.0)));
}

TEST_CASE("Joint map files", "[skeleton][skin]") {
  const auto dir = test::fresh_temp_dir("joint_map");
  const std::string path = (dir / "map.txt").string();
  std::ofstream(path) << "# garment -> avatar\nhips Hips\n\nspine  Spine # trailing\n";
  const JointMap map = read_joint_map(path);
  REQUIRE(map.size() == 2);
  REQUIRE(map[1] == std::make_pair(std::string("spine"), std::string("Spine")));
  std::ofstream(path) << "hips Hips\nhips Root\n";
  REQUIRE_THROWS_WITH(read_joint_map(path), Catch::Contains("mapped twice"));
  std::ofstream(path) << "hips\n";
  REQUIRE_THROWS_AS(read_joint_map(path), InputError);
}

}  // namespace
}  // namespace gr
