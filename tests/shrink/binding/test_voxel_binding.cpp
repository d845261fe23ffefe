#include <iostream>

#include <catch2/catch.hpp>

#include "core/common/stopwatch.hpp"
#include "core/io/obj_document.hpp"
#include "core/io/rig_files.hpp"
#include "core/mesh/primitives.hpp"
#include "core/mesh/simulation_mesh.hpp"
#include "shrink/binding/voxel_binding.hpp"
#include "test_support.hpp"

using namespace gr;

namespace {

/// Two separate parts: a large "thigh" ball with its bone off to one side, and a small
/// "hand" ball beside it whose bone is nearer than the thigh's bone to the thigh's vertices
/// facing the hand. Joints 0-1: the thigh bone; 2-3: the hand bone.
struct ThighAndHand {
  TriangleMesh avatar;
  Skeleton skeleton;
  int thigh_vertices = 0;  ///< the first vertices belong to the thigh ball
};

ThighAndHand thigh_and_hand() {
  const TriangleMesh thigh = uv_sphere(1.0, Vector3d::Zero(), 16, 32);
  const TriangleMesh hand = uv_sphere(0.3, Vector3d(1.5, 0.0, 0.0), 10, 20);
  ThighAndHand scene;
  scene.thigh_vertices = static_cast<int>(thigh.vertices.rows());
  scene.avatar.vertices.resize(thigh.vertices.rows() + hand.vertices.rows(), 3);
  scene.avatar.vertices << thigh.vertices, hand.vertices;
  scene.avatar.faces.resize(thigh.faces.rows() + hand.faces.rows(), 3);
  scene.avatar.faces << thigh.faces, hand.faces.array() + scene.thigh_vertices;
  scene.skeleton.joints.resize(4, 3);
  scene.skeleton.joints << -0.6, 0, -0.3, -0.6, 0, 0.3, 1.5, 0, -0.1, 1.5, 0, 0.1;
  scene.skeleton.bones.resize(2, 2);
  scene.skeleton.bones << 0, 1, 2, 3;
  return scene;
}

/// Weights in the layout of a skin file: non-negative columns summing to 1 with at most
/// `influences` non-zeros.
void require_skin_layout(const Eigen::MatrixXd& weights, int influences) {
  for (Eigen::Index v = 0; v < weights.cols(); ++v) {
    CAPTURE(v);
    REQUIRE(weights.col(v).minCoeff() >= 0.0);
    REQUIRE(weights.col(v).sum() == Approx(1.0).epsilon(1e-12));
    REQUIRE((weights.col(v).array() > 0.0).count() <= influences);
  }
}

struct SharedAvatar {
  TriangleMesh mesh;
  SimulationMesh sim;
  Skeleton skeleton;
};

SharedAvatar shared_avatar(const std::string& name) {
  SharedAvatar avatar;
  avatar.sim = make_simulation_mesh(read_obj(test::shared_data("avatars/" + name + "/avatar.obj")));
  avatar.mesh = avatar.sim.mesh;
  avatar.skeleton = read_skeleton(test::shared_data("avatars/" + name + "/skeleton.obj"));
  return avatar;
}

}  // namespace

TEST_CASE("binding reaches bones only through the body", "[shrink][binding]") {
  const ThighAndHand scene = thigh_and_hand();
  // The thigh vertex facing the hand is nearer the hand's bone than its own: a nearest-bone
  // binding puts it on the hand.
  Eigen::Index facing = 0;
  scene.avatar.vertices.topRows(scene.thigh_vertices).col(0).maxCoeff(&facing);
  const Vector3d p = scene.avatar.vertices.row(facing).transpose();
  REQUIRE((p - Vector3d(1.5, 0, 0)).norm() < (p - Vector3d(-0.6, 0, 0)).norm());

  BindingOptions options;
  options.method =
      GENERATE(BindingMethod::kGeodesic, BindingMethod::kVisible, BindingMethod::kHeat);
  // End segments inside the balls: the visible method sees no bone point outside the body.
  options.end_length = 0.5;
  CAPTURE(to_string(options.method));
  const Binding binding = bind_skeleton(scene.avatar, scene.skeleton, options);
  require_skin_layout(binding.weights, options.max_influences);
  REQUIRE(binding.segments == 4);  // two bones and the end segment beyond each
  REQUIRE(binding.vertices_through_interior == scene.avatar.vertices.rows());
  const Eigen::Index thigh = scene.thigh_vertices;
  const Eigen::Index hand = scene.avatar.vertices.rows() - thigh;
  REQUIRE(binding.weights.bottomLeftCorner(2, thigh).maxCoeff() == 0.0);
  REQUIRE(binding.weights.topRightCorner(2, hand).maxCoeff() == 0.0);
  // The bone's weight goes to its joint nearer the root, the end segment's to its end joint.
  Eigen::Index dominant = -1;
  binding.weights.col(facing).maxCoeff(&dominant);
  REQUIRE(dominant == 0);
  Eigen::Index top = 0;
  scene.avatar.vertices.topRows(thigh).col(2).maxCoeff(&top);
  binding.weights.col(top).maxCoeff(&dominant);
  REQUIRE(dominant == 1);
}

TEST_CASE("binding does not depend on the avatar's units", "[shrink][binding]") {
  ThighAndHand scene = thigh_and_hand();
  BindingOptions options;
  options.method = GENERATE(BindingMethod::kGeodesic, BindingMethod::kHeat);
  CAPTURE(to_string(options.method));
  const Binding unit = bind_skeleton(scene.avatar, scene.skeleton, options);
  // A power of two keeps every coordinate's rounding, so the voxels are the same.
  scene.avatar.vertices *= 1.0 / 1024.0;
  scene.skeleton.joints *= 1.0 / 1024.0;
  const Binding small = bind_skeleton(scene.avatar, scene.skeleton, options);
  REQUIRE(small.voxel_size == Approx(unit.voxel_size / 1024.0));
  REQUIRE((small.weights - unit.weights).cwiseAbs().maxCoeff() < 1e-9);
}

TEST_CASE("bone heat blends two limbs of one part", "[shrink][binding]") {
  // One connected part: an ellipsoid along x with a bone in each half (joints 0-1-2).
  TriangleMesh avatar = uv_sphere(1.0, Vector3d::Zero(), 16, 32);
  avatar.vertices.col(0) *= 2.0;
  avatar.vertices.rightCols(2) *= 0.5;
  Skeleton skeleton;
  skeleton.joints.resize(3, 3);
  skeleton.joints << -1.5, 0, 0, 0, 0, 0, 1.5, 0, 0;
  skeleton.bones.resize(2, 2);
  skeleton.bones << 0, 1, 1, 2;
  BindingOptions options;
  options.method = BindingMethod::kHeat;
  options.max_influences = GENERATE(2, 4);
  options.end_length = 0.3;  // the end segment beyond joint 2 stays inside
  const Binding binding = bind_skeleton(avatar, skeleton, options);
  require_skin_layout(binding.weights, options.max_influences);
  REQUIRE(binding.vertices_through_interior == avatar.vertices.rows());
  int blended = 0;
  for (Eigen::Index v = 0; v < avatar.vertices.rows(); ++v) {
    const double x = avatar.vertices(v, 0);
    Eigen::Index dominant = -1;
    binding.weights.col(v).maxCoeff(&dominant);
    CAPTURE(v, x);
    if (x < -0.3) REQUIRE(dominant == 0);
    if (x > 0.3 && x < 1.4) REQUIRE(dominant == 1);
    // Heat spreads across the elbow: both bones weigh near it, unlike a nearest-bone split.
    if (std::abs(x) < 0.1 && binding.weights.col(v).head(2).minCoeff() > 0.2) ++blended;
  }
  REQUIRE(blended > 0);
}

// GCC 12.2 at -O2 once folded `options.method == kHeat` to false in bind_skeleton and
// returned the visible weights (see vertex_segment_distances' call there).
TEST_CASE("bone heat is not the visible binding", "[shrink][binding]") {
  const ThighAndHand scene = thigh_and_hand();
  BindingOptions options;
  options.end_length = 0.5;
  options.method = BindingMethod::kVisible;
  const Binding visible = bind_skeleton(scene.avatar, scene.skeleton, options);
  options.method = BindingMethod::kHeat;
  const Binding heat = bind_skeleton(scene.avatar, scene.skeleton, options);
  const double difference = (heat.weights - visible.weights).cwiseAbs().maxCoeff();
  CAPTURE(difference);
  REQUIRE(difference > 0.1);
}

TEST_CASE("bone heat falls back where a part sees no bone", "[shrink][binding]") {
  ThighAndHand scene = thigh_and_hand();
  scene.skeleton.bones.conservativeResize(1, 2);  // the hand's bone is gone
  BindingOptions options;
  options.method = BindingMethod::kHeat;
  const Binding binding = bind_skeleton(scene.avatar, scene.skeleton, options);
  require_skin_layout(binding.weights, options.max_influences);
  REQUIRE(binding.vertices_by_straight_line == scene.avatar.vertices.rows() - scene.thigh_vertices);
}

TEST_CASE("binding refuses bad input", "[shrink][binding]") {
  const ThighAndHand scene = thigh_and_hand();
  BindingOptions options;
  options.resolution = 4;
  REQUIRE_THROWS_AS(bind_skeleton(scene.avatar, scene.skeleton, options), std::invalid_argument);
  options = {};
  options.root_joint = 4;
  REQUIRE_THROWS_AS(bind_skeleton(scene.avatar, scene.skeleton, options), std::invalid_argument);
  Skeleton boneless{scene.skeleton.joints, MatrixX2i(0, 2)};
  REQUIRE_THROWS_AS(bind_skeleton(scene.avatar, boneless), std::invalid_argument);
  REQUIRE_THROWS_AS(compare_skin_weights(Eigen::MatrixXd::Ones(2, 3), Eigen::MatrixXd::Ones(3, 2)),
                    std::invalid_argument);
}

TEST_CASE("weight agreement", "[shrink][binding]") {
  Eigen::MatrixXd a(3, 2), b(3, 2);
  a << 1, 0.5, 0, 0.5, 0, 0;
  b << 1, 0, 0, 0.25, 0, 0.75;
  const WeightAgreement agreement = compare_skin_weights(a, b);
  REQUIRE(agreement.vertices == 2);
  REQUIRE(agreement.mean_agreement == Approx((1.0 + 0.25) / 2));
  REQUIRE(agreement.dominant_match == Approx(0.5));
}

// Reads ../shared/data. The goblin's given weights are rigid (one joint per vertex), so the
// agreement of blended weights with them is below the share of matching dominant joints.
TEST_CASE("binding the shared avatars", "[shrink][binding][shared]") {
  const std::string name = GENERATE(as<std::string>{}, "goblin", "foxgirl");
  BindingOptions options;
  options.method =
      GENERATE(BindingMethod::kGeodesic, BindingMethod::kVisible, BindingMethod::kHeat);
  CAPTURE(name, to_string(options.method));
  const SharedAvatar avatar = shared_avatar(name);
  const Binding binding = bind_skeleton(avatar.mesh, avatar.skeleton, options);
  require_skin_layout(binding.weights, options.max_influences);
  std::cout << name << " " << to_string(options.method) << ": " << binding.seconds << " s, voxel "
            << binding.voxel_size << ", " << binding.interior_voxels << " interior voxels, "
            << binding.vertices_through_interior << "/" << binding.vertices_through_neighbours
            << "/" << binding.vertices_by_straight_line << " vertices, " << binding.vertices_rebound
            << " rebound\n";
  REQUIRE(binding.vertices_by_straight_line == 0);
  if (options.method == BindingMethod::kGeodesic)
    REQUIRE(binding.vertices_through_interior > 0.95 * avatar.mesh.vertices.rows());
  if (name != "goblin") return;
  const auto joints = static_cast<int>(avatar.skeleton.joints.rows());
  const Eigen::MatrixXd file =
      read_skin_weights(test::shared_data("avatars/goblin/skin.txt"), joints,
                        static_cast<int>(avatar.sim.obj_to_sim.size()));
  Eigen::MatrixXd given(joints, avatar.mesh.vertices.rows());
  for (std::size_t s = 0; s < avatar.sim.sim_to_obj.size(); ++s)
    given.col(static_cast<Eigen::Index>(s)) = file.col(avatar.sim.sim_to_obj[s]);
  const WeightAgreement agreement = compare_skin_weights(binding.weights, given);
  std::cout << "  agreement " << agreement.mean_agreement << ", dominant joint "
            << agreement.dominant_match << " over " << agreement.vertices << " vertices\n";
  REQUIRE(agreement.vertices == avatar.mesh.vertices.rows());
  // Measured 0.78 and 0.91 (geodesic); the mismatches lie along the borders between
  // neighbouring joints' regions.
  if (options.method == BindingMethod::kGeodesic) {
    REQUIRE(agreement.mean_agreement > 0.75);
    REQUIRE(agreement.dominant_match > 0.88);
  }
  // Measured 0.74 and 0.87 (heat): above the visible distances it starts from (0.67, 0.71),
  // below the geodesic; a quarter of the vertices see no bone and are heated along the
  // surface of their part only.
  if (options.method == BindingMethod::kHeat) {
    REQUIRE(agreement.mean_agreement > 0.72);
    REQUIRE(agreement.dominant_match > 0.85);
  }
}
