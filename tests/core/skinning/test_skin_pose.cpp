#include <algorithm>
#include <cmath>

#include <catch2/catch.hpp>

#include "core/io/gltf_document.hpp"
#include "core/io/gltf_fixture.hpp"
#include "core/skinning/skin_pose.hpp"
#include "scenes/synthetic/bending_arm.hpp"
#include "test_support.hpp"

namespace gr {
namespace {

double largest_gap(const MatrixX3d& a, const MatrixX3d& b) {
  return (a - b).rowwise().norm().maxCoeff();
}

/// The scene's arm.glb in `dir`, and beside it armature.glb: the arm under an armature
/// turned, scaled and moved, as exporters write one, so that the joints' worlds pass
/// through a node that is not a joint. Returns the latter's path.
std::string write_arm_under_armature(const BendingArmScene& scene,
                                     const std::filesystem::path& dir) {
  write_bending_arm_scene(scene, dir.string());
  const std::string path = (dir / "armature.glb").string();
  test::put_under_armature((dir / "arm.glb").string(), path, false);
  return path;
}

TEST_CASE("posing a skin at its rest values gives back the positions read",
          "[skinning][animation]") {
  const auto dir = test::fresh_temp_dir("skin_pose_rest");
  const BendingArmScene scene = make_bending_arm_scene(90.0);
  const std::string path = write_arm_under_armature(scene, dir);

  const GltfAsset asset = read_gltf(path);
  REQUIRE(asset.gltf.skin);
  const SkinBinding& skin = *asset.gltf.skin;
  CHECK_FALSE(skin.joints[0].parent_offset.isIdentity(1e-9));
  // The armature moved the read arm away from where it was written.
  CHECK(largest_gap(asset.document.positions, scene.arm.positions) > 0.5);

  const AnimationClip still;  // no channel: every joint at rest
  const std::vector<Eigen::Matrix4d> worlds =
      posed_joint_worlds(skin, still, bind_clip(skin, still, ClipTranslations::kAll), 0.0);
  for (std::size_t j = 0; j < skin.joints.size(); ++j)
    CHECK((worlds[j] - skin.joints[j].world).cwiseAbs().maxCoeff() < 1e-12);
  const SkinnedMesh skinned = prepare_skinned_mesh(skin, asset.document.positions);
  CHECK(largest_gap(pose_skinned_mesh(skin, skinned, worlds), asset.document.positions) < 1e-12);
}

TEST_CASE("a skin under an armature, written and read back, poses as in its own file",
          "[skinning][animation][io]") {
  const auto dir = test::fresh_temp_dir("skin_pose_armature_written");
  const BendingArmScene scene = make_bending_arm_scene(90.0);
  const GltfAsset asset = read_gltf(write_arm_under_armature(scene, dir));
  const SkinBinding& skin = *asset.gltf.skin;
  // The clip bends the elbow and turns the shoulder, the root joint, about +z.
  AnimationClip clip = scene.bend;
  AnimationChannel turn;
  turn.node = skin.joints[0].name;
  turn.times = {clip.start, clip.end};
  turn.values.resize(2, 4);
  turn.values << 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, std::sin(0.2), std::cos(0.2);
  clip.channels.push_back(turn);
  const std::string written = (dir / "written.glb").string();
  write_glb_meshes(written,
                   {GlbMesh{"arm", &asset.document, &asset.gltf, asset.document.positions, &skin}},
                   {clip});

  const GltfAsset again = read_gltf(written);
  REQUIRE(again.gltf.skin);
  const SkinBinding& read_back = *again.gltf.skin;
  REQUIRE(read_back.joints.size() == skin.joints.size());
  CHECK(read_back.joints[0].parent_offset_name == "Armature");
  CHECK(largest_gap(again.document.positions, asset.document.positions) < 1e-5);
  // The clip sets the joints' own transforms under the armature, in either file alike: a
  // file with the armature baked into its root joint would lose the armature's turn and
  // scale as soon as a clip set that joint.
  REQUIRE(bind_clip(skin, clip, ClipTranslations::kAll).driven_joints == 2);
  for (const double time : {0.0, 0.5, 1.0}) {
    const std::vector<Eigen::Matrix4d> own =
        posed_joint_worlds(skin, clip, bind_clip(skin, clip, ClipTranslations::kAll), time);
    const std::vector<Eigen::Matrix4d> back = posed_joint_worlds(
        read_back, clip, bind_clip(read_back, clip, ClipTranslations::kAll), time);
    for (std::size_t j = 0; j < own.size(); ++j)
      CHECK((own[j] - back[j]).cwiseAbs().maxCoeff() < 1e-6);
  }
  // The written clip drives the joints, never the armature.
  const tinygltf::Model model = test::load_glb(written);
  int armature = -1;
  for (std::size_t n = 0; n < model.nodes.size(); ++n)
    if (model.nodes[n].name == "Armature") armature = static_cast<int>(n);
  REQUIRE(armature >= 0);
  // One node more than the mesh and its joints: the armature, and nothing for the joints
  // right under their parent joints.
  CHECK(model.nodes.size() == skin.joints.size() + 2);
  REQUIRE(model.animations.size() == 1);
  for (const tinygltf::AnimationChannel& channel : model.animations[0].channels)
    CHECK(channel.target_node != armature);
}

TEST_CASE("a bent elbow turns the forearm rigidly and blends the band around it",
          "[skinning][animation]") {
  const BendingArmScene scene = make_bending_arm_scene(90.0);
  const SkinBinding& skin = scene.arm_skin;
  const ClipBinding binding = bind_clip(skin, scene.bend, ClipTranslations::kAll);
  CHECK(binding.driven_joints == 1);
  CHECK(binding.unmatched_nodes.empty());
  const SkinnedMesh skinned = prepare_skinned_mesh(skin, scene.arm.positions);
  const MatrixX3d bent =
      pose_skinned_mesh(skin, skinned, posed_joint_worlds(skin, scene.bend, binding, 1.0));
  for (Eigen::Index v = 0; v < bent.rows(); ++v) {
    const Eigen::Vector3d rest = scene.arm.positions.row(v).transpose();
    const Eigen::Vector3d now = bent.row(v).transpose();
    if (rest.x() > 1.2) {  // on the forearm: a quarter turn about +z through the elbow
      CHECK(now.x() == Approx(1.0 - rest.y()).margin(1e-12));
      CHECK(now.y() == Approx(rest.x() - 1.0).margin(1e-12));
      CHECK(now.z() == Approx(rest.z()).margin(1e-12));
    } else if (rest.x() < 0.8) {  // on the upper arm: still
      CHECK((now - rest).norm() < 1e-12);
    }
  }
}

TEST_CASE("a clip from another rig moves only the root joints by its translations",
          "[skinning][animation]") {
  const BendingArmScene scene = make_bending_arm_scene(90.0);
  AnimationClip clip = scene.bend;
  AnimationChannel stretch;  // a longer forearm: the other rig's elbow sits further out
  stretch.node = "wrist";
  stretch.path = ChannelPath::kTranslation;
  stretch.times = {0.0};
  stretch.values.resize(1, 3);
  stretch.values << 1.5, 0.0, 0.0;
  AnimationChannel lift = stretch;  // the whole arm raised
  lift.node = "shoulder";
  lift.values << 0.0, 0.25, 0.0;
  clip.channels.push_back(stretch);
  clip.channels.push_back(lift);
  AnimationChannel unknown = lift;
  unknown.node = "tail";
  clip.channels.push_back(unknown);
  const SkinBinding& skin = scene.arm_skin;

  const ClipBinding roots = bind_clip(skin, clip, ClipTranslations::kRoots);
  const std::vector<Eigen::Matrix4d> kept = posed_joint_worlds(skin, clip, roots, 0.0);
  CHECK(kept[0].topRightCorner<3, 1>().isApprox(Eigen::Vector3d(0.0, 0.25, 0.0)));
  CHECK(kept[2].topRightCorner<3, 1>().isApprox(Eigen::Vector3d(2.0, 0.25, 0.0)));
  REQUIRE(roots.unmatched_nodes.size() == 1);
  CHECK(roots.unmatched_nodes.front() == "tail");

  const ClipBinding all = bind_clip(skin, clip, ClipTranslations::kAll);
  CHECK(posed_joint_worlds(skin, clip, all, 0.0)[2].topRightCorner<3, 1>().isApprox(
      Eigen::Vector3d(2.5, 0.25, 0.0)));
}

TEST_CASE("a clip is sampled from its start to its end at the frame rate", "[animation]") {
  AnimationClip idle;
  idle.start = 1.0 / 30.0;
  idle.end = 8.4;
  const std::vector<double> times = frame_times(idle, 30.0);
  CHECK(times.size() == 252);
  CHECK(times.back() == Approx(8.4));
  AnimationClip instant;
  CHECK(frame_times(instant, 30.0).size() == 1);
}

}  // namespace
}  // namespace gr
