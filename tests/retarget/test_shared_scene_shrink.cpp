// The shrink module on the shared scenes, placed as the pipeline normalizes them: the
// avatars' level sets and winding numbers against brute-force oracles, and both shrinks
// certified or failing with a named conflict.
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include <catch2/catch.hpp>

#include "normalized_shared_scene.hpp"
#include "retarget/scene/normalization.hpp"
#include "retarget/scene/scene.hpp"
#include "shrink/level_set/grid_distance_field.hpp"
#include "shrink/level_set/signed_distance_grid.hpp"
#include "shrink/level_set/triangle_tree.hpp"
#include "shrink/shrink_oracles.hpp"
#include "shrink/shrunk_avatar/levelset_shrink.hpp"
#include "shrink/shrunk_avatar/shrink_certification.hpp"
#include "shrink/shrunk_avatar/skeleton_shrink.hpp"

using namespace gr;
using test::brute_force_distance;
using test::brute_force_winding_number;
using test::has_coincident_corners;
using test::require_certified;

TEST_CASE("signed distance of the shared avatars: sign and distance", "[shrink][sdf]") {
  const std::string avatar_dir = GENERATE(as<std::string>{}, "foxgirl", "goblin");
  const std::string garment_dir = avatar_dir == "foxgirl" ? "skirt" : "puffer";
  const test::NormalizedScene scene = test::load_normalized_scene(garment_dir, avatar_dir);
  const double h = 0.01;
  const SignedDistanceGrid grid = build_signed_distance(scene.avatar, h);
  const GridDistanceField field(grid);

  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_int_distribution<Eigen::Index> vertex(0, scene.avatar.vertices.rows() - 1);
  const Vector3d lo = scene.avatar.vertices.colwise().minCoeff().transpose().array() - 0.05;
  const Vector3d size =
      scene.avatar.vertices.colwise().maxCoeff().transpose().array() + 0.05 - lo.array();
  int inside = 0, outside = 0;
  double worst_error = 0.0;
  for (int trial = 0; trial < 300; ++trial) {
    // Half uniform in the box, half near the surface (where the sign is hard).
    const Vector3d p =
        trial % 2 == 0
            ? Vector3d(lo + size.cwiseProduct(Vector3d(unit(rng), unit(rng), unit(rng))))
            : Vector3d(scene.avatar.vertices.row(vertex(rng)).transpose() +
                       0.06 * Vector3d(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5));
    const double winding = test::brute_force_winding_number(scene.avatar, p);
    const double distance = test::brute_force_distance(scene.avatar, p);
    const double phi = field.evaluate(p);
    CAPTURE(avatar_dir, p.transpose(), winding, distance, phi);
    // Within a voxel of the surface the spline may smooth across it; elsewhere the sign
    // must agree with the oracle (clear cases only: far from a winding number of 1/2).
    if (distance > 1.5 * h && std::abs(std::abs(winding) - 0.5) > 0.05) {
      const bool oracle_inside = std::abs(winding) > 0.5;
      REQUIRE((phi < 0.0) == oracle_inside);
      (oracle_inside ? inside : outside)++;
    }
    if (std::abs(winding) > 0.6 || distance < grid.background() - 3 * h) {
      REQUIRE(std::abs(std::abs(phi) - distance) < h);
      worst_error = std::max(worst_error, std::abs(std::abs(phi) - distance));
    }
  }
  CHECK(inside > 10);
  CHECK(outside > 10);
  INFO("largest distance error / voxel " << worst_error / h);
  CHECK(worst_error < 0.75 * h);
  // Voxels within a few voxels of the surface get their sign carried from a nearby voxel
  // across the triangles between them: compare with the voxel's own winding number where
  // that is clear (goblin has many open parts, foxgirl overlapping ones).
  const TriangleTree tree(scene.avatar);
  std::mt19937 sign_rng(23);
  std::uniform_int_distribution<int> step(-4, 4);
  int checked = 0, inside_near = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const Eigen::Vector3i ijk = (scene.avatar.vertices.row(vertex(sign_rng)).transpose() / h)
                                    .array()
                                    .round()
                                    .cast<int>()
                                    .matrix() +
                                Eigen::Vector3i(step(sign_rng), step(sign_rng), step(sign_rng));
    const double winding = tree.winding_number(h * ijk.cast<double>());
    if (std::abs(std::abs(winding) - 0.5) < 0.05) continue;
    const double value = grid.voxel_value(ijk);
    CAPTURE(avatar_dir, ijk.transpose(), winding, value);
    REQUIRE((value < 0.0) == winding_number_inside(winding));
    ++checked;
    inside_near += value < 0.0;
  }
  CHECK(checked > 2500);
  CHECK(inside_near > 300);
}

TEST_CASE("fast winding number and distance on the shared avatars", "[shrink][winding]") {
  const std::string avatar_dir = GENERATE(as<std::string>{}, "foxgirl", "goblin");
  const std::string garment_dir = avatar_dir == "foxgirl" ? "skirt" : "puffer";
  const test::NormalizedScene scene = test::load_normalized_scene(garment_dir, avatar_dir);
  const TriangleTree tree(scene.avatar);
  const Eigen::AlignedBox3d box = tree.bounds();
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double worst = 0.0;
  int inside = 0;
  for (int trial = 0; trial < 150; ++trial) {
    const Vector3d p =
        box.min() + box.sizes().cwiseProduct(Vector3d(unit(rng), unit(rng), unit(rng)));
    const double oracle = brute_force_winding_number(scene.avatar, p);
    const double fast = tree.winding_number(p);
    CAPTURE(avatar_dir, p.transpose(), oracle, fast);
    REQUIRE(tree.exact_winding_number(p) == Approx(oracle).margin(1e-9));
    REQUIRE(std::abs(fast - oracle) < 0.02);
    worst = std::max(worst, std::abs(fast - oracle));
    inside += oracle > 0.5;
    REQUIRE(std::sqrt(tree.distance_sq(p)) ==
            Approx(brute_force_distance(scene.avatar, p)).margin(1e-12));
  }
  // The samples reach both sides: the sign test below is not vacuous.
  CHECK(inside > 5);
  INFO("largest fast winding number error " << worst);
  CHECK(worst < 0.01);
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

TEST_CASE("levelset shrink on the shared scenes: certified or a named conflict",
          "[shrink][levelset]") {
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
  const ShrinkResult result =
      shrink_to_skeleton(scene.avatar, scene.garment, scene.source_skeleton, scene.target_skeleton,
                         scene.skin_weights, options);
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
  const ShrinkResult result =
      shrink_to_skeleton(scene.avatar, scene.garment, scene.source_skeleton, scene.target_skeleton,
                         scene.skin_weights, options);
  require_certified(scene.avatar, result, scene.garment);
  REQUIRE(result.collapse_rounds >= 1);
  REQUIRE(result.collapsed_vertices > 0);
  // The fix is local: a small part of the avatar moves toward joints.
  REQUIRE(result.collapsed_vertices < scene.avatar.vertices.rows() / 20);
  REQUIRE(result.pullback == options.pullback);
  REQUIRE_FALSE(has_coincident_corners({result.vertices, scene.avatar.faces}));
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
