// Skeleton-free scenes of every family, at several resolutions, offsets and rigid motions:
// each is certified, keeps its size and shape, and both solves converge in few steps.
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/io/mesh_file.hpp"
#include "extremes_support.hpp"
#include "scenes/synthetic/skeleton_free_scenes.hpp"

namespace gr {
namespace {

/// Newton steps of the inflation and the fit together: a few hundred at most.
constexpr int kMaxNewtonSteps = 300;

struct Case {
  SkeletonFreeFamily family;
  SkeletonFreeVariant variant;
};

std::vector<Case> cases() {
  std::vector<Case> all;
  for (const SkeletonFreeFamily family : all_skeleton_free_families()) {
    all.push_back({family, {8, 0.0, 0.0, 1.0, Vector3d::Zero()}});
    all.push_back({family, {20, 0.02, 0.0, 1.0, Vector3d::Zero()}});
    // Another up axis, centimetres-like units and a far origin.
    all.push_back({family, {12, 0.0, 40.0, 37.0, Vector3d(5.0, -3.0, 2.0)}});
  }
  return all;
}

}  // namespace

TEST_CASE("skeleton-free families: certified, size and shape kept, converged in few steps",
          "[pipeline][skeleton-free]") {
  const std::vector<Case> all = cases();
  const auto index = GENERATE_COPY(range(std::size_t(0), all.size()));
  const Case& c = all[index];
  const SkeletonFreeScene scene = make_skeleton_free_scene(c.family, c.variant);
  INFO(scene.name);
  const std::filesystem::path dir = test::fresh_temp_dir("skeleton_free");
  write_obj((dir / "garment.obj").string(), scene.garment);
  write_obj((dir / "avatar.obj").string(), scene.avatar);
  RetargetOptions options = test::quiet_options((dir / "garment.obj").string(),
                                                (dir / "avatar.obj").string(), dir / "out");
  options.quality = Quality::kBalanced;
  const RetargetResult result = test::run_and_check(options);
  const RetargetReport& r = result.report;
  INFO(result.message);
  CHECK(result.status == Outcome::kCertified);
  CHECK(r.certified());
  CHECK(r.certify.shape.scale >= 0.9);
  CHECK(r.certify.shape.scale <= 1.1);
  CHECK(r.certify.shape.mean_edge_change <= 0.1);
  CHECK(r.inflate.status == "snapped");
  CHECK(r.fit.status == "converged");
  CHECK(r.inflate.newton_iterations + r.fit.newton_iterations <= kMaxNewtonSteps);
}

}  // namespace gr

namespace gr {

TEST_CASE("skeleton-free: an erosion deeper than the distance band builds a full-depth grid",
          "[pipeline][skeleton-free][shrink]") {
  // The sphere bulges 0.15 through a sleeve of radius 0.85: deeper than the band of 0.1.
  const std::filesystem::path dir = test::fresh_temp_dir("skeleton_free_deep");
  write_obj((dir / "garment.obj").string(), open_cylinder(0.85, -0.5, 0.5, 8, 24));
  write_obj((dir / "avatar.obj").string(), test::uv_sphere(32, 16));
  RetargetOptions options = test::quiet_options((dir / "garment.obj").string(),
                                                (dir / "avatar.obj").string(), dir / "out");
  options.overrides.set("voxel_size", 0.03);
  const RetargetResult result = test::run_and_check(options);
  INFO(result.message);
  CHECK(result.status == Outcome::kCertified);
  CHECK(result.report.shrink.full_depth_grid);
  CHECK(result.report.shrink.depth > kDistanceBand);
}

}  // namespace gr
