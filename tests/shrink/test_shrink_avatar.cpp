#include <algorithm>
#include <cmath>
#include <limits>

#include <catch2/catch.hpp>

#include "core/mesh/primitives.hpp"
#include "shrink/level_set/signed_distance_grid.hpp"
#include "shrink/shrunk_avatar/levelset_shrink.hpp"
#include "shrink/shrunk_avatar/shrink_certification.hpp"
#include "shrink/shrunk_avatar/skeleton_shrink.hpp"
#include "shrink_oracles.hpp"
#include "validate/checks/mesh_intersections.hpp"

using namespace gr;

namespace {

/// A flat square in the z = 0 plane, centred at the origin, split into two triangles.
TriangleMesh square(double half_side) {
  TriangleMesh mesh;
  mesh.vertices.resize(4, 3);
  mesh.vertices << -half_side, -half_side, 0, half_side, -half_side, 0, half_side, half_side, 0,
      -half_side, half_side, 0;
  mesh.faces.resize(2, 3);
  mesh.faces << 0, 1, 2, 0, 2, 3;
  return mesh;
}

}  // namespace

TEST_CASE("levelset shrink pulls the body off a garment wholly inside it", "[shrink][levelset]") {
  const TriangleMesh avatar = uv_sphere(0.5, Vector3d::Zero());
  const TriangleMesh garment = uv_sphere(0.35, Vector3d(0.02, 0.0, 0.0), 12, 24);
  // No surface crosses: only the inside test sees the conflict.
  REQUIRE(find_intersecting_face_pairs(avatar, garment).count == 0);
  const double h = 0.02;
  const SignedDistanceGrid grid = build_signed_distance(avatar, h);
  const ShrinkResult result = shrink_levelset(avatar, garment, grid);
  test::require_certified(avatar, result, garment);
  // The eroded sphere must sit inside the garment sphere (radius 0.35 off by 0.02): d >= 0.13.
  REQUIRE(result.depth > 0.13);
  REQUIRE(result.depth < 0.5);
  REQUIRE(result.medial_vertices == 0);
  // Vertices sit on phi = -d: radius 0.5 - d, up to the spline's smoothing.
  for (Eigen::Index v = 0; v < result.vertices.rows(); ++v)
    REQUIRE(result.vertices.row(v).norm() == Approx(0.5 - result.depth).margin(0.5 * h));
  REQUIRE(result.certifications >= 3);
}

TEST_CASE("levelset shrink keeps an avatar already free of the garment", "[shrink][levelset]") {
  const TriangleMesh avatar = uv_sphere(0.5, Vector3d::Zero());
  const TriangleMesh garment = uv_sphere(0.7, Vector3d::Zero(), 12, 24);
  const ShrinkResult result = shrink_levelset(avatar, garment, build_signed_distance(avatar, 0.02));
  REQUIRE(result.depth == 0.0);
  REQUIRE((result.vertices - avatar.vertices).cwiseAbs().maxCoeff() < 0.01);
  test::require_certified(avatar, result, garment);
}

TEST_CASE("levelset shrink names the crossing when no depth works", "[shrink][levelset]") {
  const TriangleMesh avatar = uv_sphere(0.5, Vector3d::Zero());
  // A sheet through the centre crosses every eroded sphere, down to the medial point.
  const TriangleMesh garment = square(0.8);
  try {
    shrink_levelset(avatar, garment, build_signed_distance(avatar, 0.02));
    FAIL("expected NoValidShrinkError");
  } catch (const NoValidShrinkError& e) {
    const ShrinkConflict& conflict = e.conflict();
    REQUIRE(conflict.kind == ShrinkConflict::Kind::kSurfacesCross);
    REQUIRE(conflict.avatar_face >= 0);
    REQUIRE(conflict.avatar_face < avatar.faces.rows());
    REQUIRE(conflict.garment_face >= 0);
    REQUIRE(conflict.position.norm() < 0.5);
    REQUIRE(std::abs(conflict.position.z()) < 1e-9);
    REQUIRE(std::string(e.what()).find("garment face") != std::string::npos);
  }
}

TEST_CASE("skeleton shrink pulls a face spanning a bent skeleton toward the joint",
          "[shrink][skeleton]") {
  // An L of bones 0-1 (along x) and 1-2 (along y), and one avatar triangle with a corner on
  // each arm of the L and one above it. A small square garment sheet across the triangle's
  // middle stays clear of the bones; the triangle must shrink toward joint 1 to clear it.
  // With a third bone 2-3 the triangle's second arm is two bones away from the first:
  // it then shrinks toward the bone between them.
  const bool chain = GENERATE(false, true);
  CAPTURE(chain);
  Skeleton skeleton;
  if (chain) {
    skeleton.joints.resize(4, 3);
    skeleton.joints << 0, 0, 0, 1, 0, 0, 1, 0.5, 0, 1, 1.5, 0;
    skeleton.bones.resize(3, 2);
    skeleton.bones << 0, 1, 1, 2, 2, 3;
  } else {
    skeleton.joints.resize(3, 3);
    skeleton.joints << 0, 0, 0, 1, 0, 0, 1, 1.5, 0;
    skeleton.bones.resize(2, 2);
    skeleton.bones << 0, 1, 1, 2;
  }
  TriangleMesh avatar;
  avatar.vertices.resize(3, 3);
  avatar.vertices << 0.2, 0.0, 0.01, 1.0, 0.8, 0.01, 1.0, 1.0, 0.02;
  avatar.faces.resize(1, 3);
  avatar.faces << 0, 1, 2;
  // A square of half side 0.1 centred on the triangle's first edge, facing along it.
  const Vector3d center(0.6, 0.4, 0.0), along = Vector3d(0.8, 0.8, 0.0).normalized();
  const Vector3d u = Vector3d::UnitZ(), w = along.cross(u);
  TriangleMesh garment = square(0.1);
  for (Eigen::Index v = 0; v < 4; ++v)
    garment.vertices.row(v) =
        (center + garment.vertices(v, 0) * u + garment.vertices(v, 1) * w).transpose();
  REQUIRE(find_intersecting_face_pairs(avatar, garment).count == 1);

  SkeletonShrinkOptions options;
  options.max_halvings = 0;
  const ShrinkResult result =
      shrink_to_skeleton(avatar, garment, skeleton, skeleton, Eigen::MatrixXd(), options);
  test::require_certified(avatar, result, garment);
  REQUIRE(result.collapsed_vertices == 3);
  REQUIRE(result.collapse_rounds >= 1);
  REQUIRE_FALSE(test::has_coincident_corners({result.vertices, avatar.faces}));
  // Every corner went toward the joints of the bend (on the path between the two arms),
  // never to the far ends of the arms.
  const Vector3d bend(1.0, chain ? 0.25 : 0.0, 0.0);
  for (Eigen::Index v = 0; v < 3; ++v) {
    CAPTURE(v, result.vertices.row(v));
    REQUIRE((result.vertices.row(v).transpose() - bend).norm() <
            (avatar.vertices.row(v).transpose() - bend).norm());
  }

  options.max_collapse_rounds = 0;
  REQUIRE_THROWS_AS(
      shrink_to_skeleton(avatar, garment, skeleton, skeleton, Eigen::MatrixXd(), options),
      NoValidShrinkError);
}

TEST_CASE("skeleton shrink pulls a corner along the bones to a joint two bones away",
          "[shrink][skeleton]") {
  // A body of two arms: bones 0-1 and 1-2 to the right (shoulder at joint 1), 0-3 and 3-4
  // to the left. One avatar triangle spans from the right arm to the left arm. A garment
  // wall at x = 1 closes the right armpit below y = 0.6: a corner going straight from the
  // right arm to joint 0 would cross it; along the bones it passes over it, by the shoulder.
  Skeleton skeleton;
  skeleton.joints.resize(5, 3);
  skeleton.joints << 0, 0, 0, 1, 1, 0, 2, 0, 0, -1, 1, 0, -2, 0, 0;
  skeleton.bones.resize(4, 2);
  skeleton.bones << 0, 1, 1, 2, 0, 3, 3, 4;
  TriangleMesh avatar;
  avatar.vertices.resize(3, 3);
  avatar.vertices << 1.8, 0.2, 0.0, -1.8, 0.2, 0.0, 0.0, 0.05, 0.01;
  avatar.faces.resize(1, 3);
  avatar.faces << 0, 1, 2;
  TriangleMesh wall;
  wall.vertices.resize(4, 3);
  wall.vertices << 1, -0.5, -0.2, 1, 0.6, -0.2, 1, 0.6, 0.2, 1, -0.5, 0.2;
  wall.faces.resize(2, 3);
  wall.faces << 0, 1, 2, 0, 2, 3;
  REQUIRE(find_intersecting_face_pairs(avatar, wall).count > 0);

  SkeletonShrinkOptions options;
  options.max_halvings = 0;
  const ShrinkResult result =
      shrink_to_skeleton(avatar, wall, skeleton, skeleton, Eigen::MatrixXd(), options);
  test::require_certified(avatar, result, wall);
  REQUIRE_FALSE(test::has_coincident_corners({result.vertices, avatar.faces}));
  // The right corner left its arm by the shoulder: it lies on the skeleton, on the right
  // side of the wall's top or past the shoulder, never in the armpit below it.
  const Vector3d corner = result.vertices.row(0).transpose();
  CAPTURE(corner.transpose());
  double to_skeleton = std::numeric_limits<double>::infinity();
  for (Eigen::Index b = 0; b < skeleton.bones.rows(); ++b) {
    const Vector3d a = skeleton.joints.row(skeleton.bones(b, 0)).transpose();
    const Vector3d d = skeleton.joints.row(skeleton.bones(b, 1)).transpose() - a;
    const double s = std::clamp((corner - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
    to_skeleton = std::min(to_skeleton, (a + s * d - corner).norm());
  }
  CHECK(to_skeleton < 0.05);
  CHECK((corner.x() >= 1.0 || corner.y() >= 0.6 || corner.x() < 0.6));
}
