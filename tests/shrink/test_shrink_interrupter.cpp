#include <optional>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/common/interrupter.hpp"
#include "core/mesh/primitives.hpp"
#include "shrink/binding/voxel_binding.hpp"
#include "shrink/level_set/signed_distance_grid.hpp"
#include "shrink/shrunk_avatar/levelset_shrink.hpp"

using namespace gr;

namespace {

/// Keeps the stages and fractions it is told; cancels after `allowed` progress reports, or
/// as soon as `stop_stage` starts.
class Cancel : public Interrupter {
 public:
  static Cancel after_reports(int allowed) { return Cancel(allowed, ""); }
  static Cancel in_stage(std::string stage) { return Cancel(-1, std::move(stage)); }

  void start(const std::string& stage) override { stages.push_back(stage); }
  void progress(double fraction) override { fractions.push_back(fraction); }
  std::optional<Interrupted> interruption() const override {
    const bool stop = (allowed_ >= 0 && static_cast<int>(fractions.size()) >= allowed_) ||
                      (!stages.empty() && stages.back() == stop_stage_);
    if (!stop) return std::nullopt;
    return Interrupted(InterruptReason::kCancelled, "cancelled during " + stages.back());
  }

  std::vector<std::string> stages;
  std::vector<double> fractions;

 private:
  Cancel(int allowed, std::string stop_stage) : allowed_(allowed), stop_stage_(stop_stage) {}
  int allowed_;
  std::string stop_stage_;
};

}  // namespace

TEST_CASE("a level-set shrink reports its bisection and stops through its interrupter",
          "[shrink][levelset][interrupter]") {
  const TriangleMesh avatar = uv_sphere(0.5, Vector3d::Zero());
  const TriangleMesh garment = uv_sphere(0.35, Vector3d(0.02, 0.0, 0.0), 12, 24);
  const SignedDistanceGrid grid = build_signed_distance(avatar, 0.02);
  Cancel never = Cancel::after_reports(1 << 30);
  LevelsetShrinkOptions options;
  options.interrupter = &never;
  const ShrinkResult whole = shrink_levelset(avatar, garment, grid, options);
  CHECK(never.stages == std::vector<std::string>{"shrink"});
  REQUIRE(never.fractions.size() >= 3);
  CHECK(never.fractions.front() == 0.0);
  CHECK(never.fractions.back() == 1.0);
  for (std::size_t k = 1; k < never.fractions.size(); ++k)
    CHECK(never.fractions[k] >= never.fractions[k - 1]);

  const int allowed = GENERATE(1, 2);
  CAPTURE(allowed);
  Cancel cancel = Cancel::after_reports(allowed);
  options.interrupter = &cancel;
  try {
    shrink_levelset(avatar, garment, grid, options);
    FAIL("the shrink was not interrupted");
  } catch (const Interrupted& stopped) {
    CHECK(stopped.reason() == InterruptReason::kCancelled);
    CHECK(std::string(stopped.what()) == "cancelled during shrink");
  }
  CHECK(static_cast<int>(cancel.fractions.size()) == allowed);
  CHECK(whole.certifications >= 3);
}

TEST_CASE("a signed distance build stops in the stage its interrupter stops it",
          "[shrink][sdf][interrupter]") {
  const TriangleMesh sphere = uv_sphere(0.5, Vector3d::Zero(), 8, 16);
  const std::vector<std::string> stages = {"unsigned distance", "sign", "interior"};
  const auto stop_in = static_cast<std::size_t>(GENERATE(0, 1, 2));
  CAPTURE(stages[stop_in]);
  Cancel cancel = Cancel::in_stage(stages[stop_in]);
  SignedDistanceOptions options;
  options.interrupter = &cancel;
  try {
    build_signed_distance(sphere, 0.05, options);
    FAIL("the build was not interrupted");
  } catch (const Interrupted& stopped) {
    CHECK(std::string(stopped.what()) == "cancelled during " + stages[stop_in]);
  }
  CHECK(cancel.stages == std::vector<std::string>(stages.begin(), stages.begin() + stop_in + 1));
  // A narrow band has no interior stage: nothing stops it.
  Cancel interior = Cancel::in_stage("interior");
  options.interrupter = &interior;
  options.full_depth = false;
  CHECK(build_signed_distance(sphere, 0.05, options).active_voxel_count() > 0);
  CHECK(interior.stages == std::vector<std::string>{"unsigned distance", "sign"});
}

TEST_CASE("a binding names its grid's stages \"binding grid\" and stops there",
          "[shrink][binding][interrupter]") {
  const TriangleMesh avatar = uv_sphere(0.5, Vector3d::Zero(), 8, 16);
  Skeleton skeleton;
  skeleton.joints.resize(2, 3);
  skeleton.joints << 0, -0.3, 0, 0, 0.3, 0;
  skeleton.bones.resize(1, 2);
  skeleton.bones << 0, 1;
  BindingOptions options;
  options.resolution = 16;
  Cancel cancel = Cancel::in_stage("binding grid");
  options.interrupter = &cancel;
  CHECK_THROWS_WITH(bind_skeleton(avatar, skeleton, options), "cancelled during binding grid");
  CHECK(cancel.stages == std::vector<std::string>{"binding", "binding grid"});

  Cancel never = Cancel::after_reports(1 << 30);
  options.interrupter = &never;
  const Binding binding = bind_skeleton(avatar, skeleton, options);
  CHECK(binding.weights.cols() == avatar.vertices.rows());
  CHECK(never.stages.front() == "binding");
  CHECK(never.stages.back() == "binding");
  CHECK(never.fractions.back() == 1.0);
}
