#include <cmath>

#include <catch2/catch.hpp>

#include "shrink/level_set/signed_distance_grid.hpp"
#include "shrink/shrunk_avatar/levelset_shrink.hpp"
#include "shrink/shrunk_avatar/shrink_certification.hpp"
#include "shrink/shrunk_avatar/skeleton_shrink.hpp"
#include "shrink_test_scenes.hpp"
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

void require_certified(const TriangleMesh& avatar, const ShrinkResult& result,
                       const TriangleMesh& garment) {
  const TriangleMesh shrunk{result.vertices, avatar.faces};
  REQUIRE(result.vertices.rows() == avatar.vertices.rows());
  REQUIRE(find_intersecting_face_pairs(shrunk, garment).count == 0);
  REQUIRE_FALSE(find_shrink_conflict(shrunk, garment).has_value());
}

}  // namespace

TEST_CASE("levelset shrink pulls the body off a garment wholly inside it", "[shrink][levelset]") {
  const TriangleMesh avatar = test::uv_sphere(0.5, Vector3d::Zero());
  const TriangleMesh garment = test::uv_sphere(0.35, Vector3d(0.02, 0.0, 0.0), 12, 24);
  // No surface crosses: only the inside test sees the conflict.
  REQUIRE(find_intersecting_face_pairs(avatar, garment).count == 0);
  const double h = 0.02;
  const SignedDistanceGrid grid = build_signed_distance(avatar, h);
  const ShrinkResult result = shrink_levelset(avatar, garment, grid);
  require_certified(avatar, result, garment);
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
  const TriangleMesh avatar = test::uv_sphere(0.5, Vector3d::Zero());
  const TriangleMesh garment = test::uv_sphere(0.7, Vector3d::Zero(), 12, 24);
  const ShrinkResult result = shrink_levelset(avatar, garment, build_signed_distance(avatar, 0.02));
  REQUIRE(result.depth == 0.0);
  REQUIRE((result.vertices - avatar.vertices).cwiseAbs().maxCoeff() < 0.01);
  require_certified(avatar, result, garment);
}

TEST_CASE("levelset shrink names the crossing when no depth works", "[shrink][levelset]") {
  const TriangleMesh avatar = test::uv_sphere(0.5, Vector3d::Zero());
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

TEST_CASE("levelset shrink of the skirt's own body is certified", "[shrink][levelset]") {
  // The body the skirt was made on, in the skirt's frame (no skeletons: one shared frame).
  ScenePaths paths;
  paths.garment = test::shared_data("garments/skirt/garment.obj");
  paths.avatar = test::shared_data("garments/skirt/source_body.obj");
  const Scene scene = load_scene(paths);
  const Normalization n = normalize_scene(scene);
  const TriangleMesh avatar{n.avatar_to_scene.apply_rows(scene.avatar.mesh.vertices),
                            scene.avatar.mesh.faces};
  const TriangleMesh garment{n.garment_to_scene.apply_rows(scene.garment.mesh.vertices),
                             scene.garment.mesh.faces};
  const ShrinkResult result = shrink_levelset(avatar, garment, build_signed_distance(avatar, 0.01));
  require_certified(avatar, result, garment);
  REQUIRE(result.depth >= 0.0);
}

TEST_CASE("levelset shrink on the shared scenes: certified or a named conflict", "[shrink][levelset]") {
  // Both shared targets differ from the source body in pose or proportions (foxgirl's hips
  // are wider than the skirt's waist's medial reach, goblin's arms hang through the
  // sleeves): erosion alone cannot free them, and the error must say where.
  const std::string avatar_dir = GENERATE(as<std::string>{}, "foxgirl", "goblin");
  const std::string garment_dir = avatar_dir == "foxgirl" ? "skirt" : "puffer";
  const test::NormalizedScene scene = test::load_normalized_scene(garment_dir, avatar_dir);
  const SignedDistanceGrid grid = build_signed_distance(scene.avatar, 0.01);
  try {
    const ShrinkResult result = shrink_levelset(scene.avatar, scene.garment, grid);
    require_certified(scene.avatar, result, scene.garment);
  } catch (const NoValidShrinkError& e) {
    const ShrinkConflict& conflict = e.conflict();
    CAPTURE(e.what());
    REQUIRE(conflict.count > 0);
    if (conflict.kind == ShrinkConflict::Kind::kSurfacesCross) {
      REQUIRE(conflict.avatar_face >= 0);
      REQUIRE(conflict.garment_face >= 0);
      // The named position lies on the named garment face's plane.
      const auto& g = scene.garment;
      const Vector3d a = g.vertices.row(g.faces(conflict.garment_face, 0)).transpose();
      const Vector3d b = g.vertices.row(g.faces(conflict.garment_face, 1)).transpose();
      const Vector3d c = g.vertices.row(g.faces(conflict.garment_face, 2)).transpose();
      const Vector3d normal = (b - a).cross(c - a).normalized();
      REQUIRE(std::abs(normal.dot(conflict.position - a)) < 0.02);
    }
  }
}

TEST_CASE("skeleton shrink of foxgirl under the skirt is certified", "[shrink][skeleton]") {
  const test::NormalizedScene scene = test::load_normalized_scene("skirt", "foxgirl");
  SkeletonShrinkOptions options;
  const ShrinkResult result = shrink_to_skeleton(scene.avatar, scene.garment, scene.source_skeleton,
                                                 scene.target_skeleton, scene.skin_weights, options);
  require_certified(scene.avatar, result, scene.garment);
  REQUIRE(result.pullback > 0.0);
  REQUIRE(result.pullback <= options.pullback);
  // Every shrunk vertex is within pullback × (its distance to the target skeleton) of a
  // source bone.
  const Skeleton& source = scene.source_skeleton;
  auto distance_to_skeleton = [](const Skeleton& s, const Vector3d& p) {
    double best = std::numeric_limits<double>::infinity();
    for (Eigen::Index b = 0; b < s.bones.rows(); ++b) {
      const Vector3d a = s.joints.row(s.bones(b, 0)).transpose();
      const Vector3d d = s.joints.row(s.bones(b, 1)).transpose() - a;
      const double t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
      best = std::min(best, (a + t * d - p).norm());
    }
    return best;
  };
  double farthest = 0.0;
  for (Eigen::Index v = 0; v < scene.avatar.vertices.rows(); ++v)
    farthest = std::max(farthest, distance_to_skeleton(scene.target_skeleton,
                                                       scene.avatar.vertices.row(v).transpose()));
  for (Eigen::Index v = 0; v < result.vertices.rows(); ++v)
    REQUIRE(distance_to_skeleton(source, result.vertices.row(v).transpose()) <=
            result.pullback * farthest * 3.0 + 1e-9);
}

namespace {

/// True when some face has two corners at exactly the same position.
bool has_coincident_corners(const TriangleMesh& mesh) {
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      if (mesh.vertices.row(mesh.faces(f, c)) == mesh.vertices.row(mesh.faces(f, (c + 1) % 3)))
        return true;
  return false;
}

}  // namespace

TEST_CASE("skeleton shrink of goblin under the puffer is certified", "[shrink][skeleton]") {
  // Goblin's arms hang down where the puffer's are raised: faces whose corners land on the
  // shoulder bone and the upper-arm bone span the armpit and cross the sleeve's underside.
  const test::NormalizedScene scene = test::load_normalized_scene("puffer", "goblin");
  SkeletonShrinkOptions bones_only;
  bones_only.max_collapse_rounds = 0;
  bones_only.max_halvings = 0;
  try {
    shrink_to_skeleton(scene.avatar, scene.garment, scene.source_skeleton, scene.target_skeleton,
                       scene.skin_weights, bones_only);
    FAIL("the bones alone were expected to leave the armpit crossing the sleeve");
  } catch (const NoValidShrinkError& e) {
    REQUIRE(e.conflict().kind == ShrinkConflict::Kind::kSurfacesCross);
  }

  const SkeletonShrinkOptions options;
  const ShrinkResult result = shrink_to_skeleton(scene.avatar, scene.garment, scene.source_skeleton,
                                                 scene.target_skeleton, scene.skin_weights, options);
  require_certified(scene.avatar, result, scene.garment);
  REQUIRE(result.collapse_rounds >= 1);
  REQUIRE(result.collapsed_vertices > 0);
  // The fix is local: a small part of the avatar moves toward joints.
  REQUIRE(result.collapsed_vertices < scene.avatar.vertices.rows() / 20);
  REQUIRE(result.pullback == options.pullback);
  REQUIRE_FALSE(has_coincident_corners({result.vertices, scene.avatar.faces}));
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
  require_certified(avatar, result, garment);
  REQUIRE(result.collapsed_vertices == 3);
  REQUIRE(result.collapse_rounds >= 1);
  REQUIRE_FALSE(has_coincident_corners({result.vertices, avatar.faces}));
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

TEST_CASE("skeleton shrink checks its inputs", "[shrink][skeleton]") {
  const test::NormalizedScene scene = test::load_normalized_scene("puffer", "goblin");
  REQUIRE(scene.skin_weights.cols() == scene.avatar.vertices.rows());
  const Eigen::MatrixXd wrong = Eigen::MatrixXd::Ones(3, 4);
  REQUIRE_THROWS_AS(shrink_to_skeleton(scene.avatar, scene.garment, scene.source_skeleton,
                                       scene.target_skeleton, wrong),
                    std::invalid_argument);
  SkeletonShrinkOptions zero;
  zero.pullback = 0.0;
  REQUIRE_THROWS_AS(shrink_to_skeleton(scene.avatar, scene.garment, scene.source_skeleton,
                                       scene.target_skeleton, scene.skin_weights, zero),
                    std::invalid_argument);
  SkeletonShrinkOptions whole_step;
  whole_step.collapse_step = 1.0;
  REQUIRE_THROWS_AS(shrink_to_skeleton(scene.avatar, scene.garment, scene.source_skeleton,
                                       scene.target_skeleton, scene.skin_weights, whole_step),
                    std::invalid_argument);
}
