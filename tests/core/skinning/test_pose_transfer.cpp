#include <cmath>

#include <catch2/catch.hpp>

#include "core/skinning/pose_transfer.hpp"
#include "scenes/synthetic/bending_arm.hpp"

namespace gr {
namespace {

Skeleton arm(const Eigen::Vector3d& wrist) {
  Skeleton skeleton;
  skeleton.joints.resize(3, 3);
  skeleton.joints << 0, 0, 0, 1, 0, 0, wrist.x(), wrist.y(), wrist.z();
  skeleton.bones.resize(2, 2);
  skeleton.bones << 0, 1, 1, 2;
  return skeleton;
}

/// Mean over the edges of |length after / length before - 1|.
double mean_edge_change(const ObjDocument& document, const MatrixX3d& after) {
  double sum = 0.0;
  int count = 0;
  for (const auto& face : document.faces)
    for (int c = 0; c < 3; ++c) {
      const int a = face[static_cast<std::size_t>(c)].position;
      const int b = face[static_cast<std::size_t>((c + 1) % 3)].position;
      const double before = (document.positions.row(a) - document.positions.row(b)).norm();
      sum += std::abs((after.row(a) - after.row(b)).norm() / before - 1.0);
      ++count;
    }
  return sum / count;
}

TEST_CASE("pose transfer turns a sleeve with a two-bone arm, its edges kept", "[skinning][pose]") {
  const BendingArmScene scene = make_bending_arm_scene(90.0);
  const Skeleton straight = arm({2, 0, 0});
  // The target's forearm is longer and points up: the turn is taken, the length is not.
  const Skeleton bent = arm({1, 1.5, 0});
  const std::vector<Eigen::Isometry3d> motions = pose_transfer_motions(straight, bent);
  const MatrixX3d joints = moved_joints(straight, motions);
  CHECK((joints.row(2) - Eigen::RowVector3d(1, 1, 0)).norm() < 1e-12);
  CHECK(joints.row(0).norm() < 1e-12);

  // The sleeve's weights step at the elbow: each half moves rigidly.
  const MatrixX3d posed = skin_by_motions(scene.sleeve.positions, scene.sleeve_skin.weights,
                                          motions, SkinningMethod::kLinearBlend);
  for (Eigen::Index v = 0; v < posed.rows(); ++v) {
    const Eigen::Vector3d rest = scene.sleeve.positions.row(v).transpose();
    if (rest.x() < 1.0) CHECK((posed.row(v).transpose() - rest).norm() < 1e-12);
    if (rest.x() > 1.0) {
      CHECK(posed(v, 0) == Approx(1.0 - rest.y()).margin(1e-12));
      CHECK(posed(v, 1) == Approx(rest.x() - 1.0).margin(1e-12));
    }
  }
  // Only the ring of faces across the elbow, where the weights step, stretches: every edge
  // with both ends on one side keeps its length.
  int kept = 0;
  int edges = 0;
  for (const auto& face : scene.sleeve.faces)
    for (int c = 0; c < 3; ++c) {
      const int a = face[static_cast<std::size_t>(c)].position;
      const int b = face[static_cast<std::size_t>((c + 1) % 3)].position;
      ++edges;
      if ((scene.sleeve.positions(a, 0) < 1.0) != (scene.sleeve.positions(b, 0) < 1.0)) continue;
      const double before = (scene.sleeve.positions.row(a) - scene.sleeve.positions.row(b)).norm();
      CHECK((posed.row(a) - posed.row(b)).norm() == Approx(before).epsilon(1e-12));
      ++kept;
    }
  CHECK(kept > 0.9 * edges);
}

TEST_CASE("dual quaternions keep a blended elbow's girth where linear blending pinches it",
          "[skinning][pose]") {
  const BendingArmScene scene = make_bending_arm_scene(90.0);
  const std::vector<Eigen::Isometry3d> motions =
      pose_transfer_motions(arm({2, 0, 0}), arm({1, 1, 0}));
  // The arm blends its bones over a band around the elbow.
  const MatrixX3d linear = skin_by_motions(scene.arm.positions, scene.arm_skin.weights, motions,
                                           SkinningMethod::kLinearBlend);
  const MatrixX3d dual = skin_by_motions(scene.arm.positions, scene.arm_skin.weights, motions,
                                         SkinningMethod::kDualQuaternion);
  // At the elbow ring (weights one half each), the distance from the elbow's axis.
  double linear_radius = 0.0;
  double dual_radius = 0.0;
  int ring = 0;
  for (Eigen::Index v = 0; v < scene.arm.positions.rows(); ++v) {
    if (std::abs(scene.arm.positions(v, 0) - 1.0) > 1e-9 ||
        std::abs(scene.arm.positions(v, 2)) > 0.01)
      continue;
    // Vertices on the bend's plane side: their distance to the elbow in the xy plane.
    linear_radius += std::hypot(linear(v, 0) - 1.0, linear(v, 1));
    dual_radius += std::hypot(dual(v, 0) - 1.0, dual(v, 1));
    ++ring;
  }
  REQUIRE(ring > 0);
  CHECK(linear_radius / ring == Approx(0.3 * std::sqrt(0.5)).epsilon(1e-9));
  CHECK(dual_radius / ring == Approx(0.3).epsilon(1e-9));
  // Both stretch the band's edges, each its own way (pinched inside, bulged outside).
  CHECK(mean_edge_change(scene.arm, linear) > 0.01);
  CHECK(mean_edge_change(scene.arm, dual) > 0.01);
  // Rigidly moved parts agree between the two.
  for (Eigen::Index v = 0; v < scene.arm.positions.rows(); ++v)
    if (scene.arm.positions(v, 0) > 1.2 || scene.arm.positions(v, 0) < 0.8)
      CHECK((linear.row(v) - dual.row(v)).norm() < 1e-9);
}

}  // namespace
}  // namespace gr
