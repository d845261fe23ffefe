// The written garment's bytes on scenes of every kind, against the SHA-256 recorded in
// tests/data/golden/garment_sha256.txt. A change that is meant to keep results (a
// restructuring, a faster data structure) must keep these; a change that is meant to
// change results records the new digests, by running this test with
// GR_UPDATE_GOLDEN=1, and says so in its commit.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "cli_runner.hpp"
#include "core/io/mesh_file.hpp"
#include "scenes/synthetic/skeleton_free_scenes.hpp"
#include "test_support.hpp"
#include "validate/report/file_digest.hpp"

namespace fs = std::filesystem;

namespace {

const fs::path kGoldenFile = fs::path(GR_SOURCE_DIR) / "tests/data/golden/garment_sha256.txt";

/// scene name → digest, from the golden file ("name digest" per line).
std::map<std::string, std::string> recorded_digests() {
  std::map<std::string, std::string> digests;
  std::ifstream in(kGoldenFile);
  std::string name, digest;
  while (in >> name >> digest) digests[name] = digest;
  return digests;
}

void record_digest(const std::string& scene, const std::string& digest) {
  std::map<std::string, std::string> digests = recorded_digests();
  digests[scene] = digest;
  std::ofstream out(kGoldenFile);
  for (const auto& [name, value] : digests) out << name << ' ' << value << '\n';
}

/// Retargets with `args` (without --out) and checks the digest of the garment written
/// (`written`, in the output folder).
void check_golden(const std::string& scene, std::vector<std::string> args,
                  const std::string& written = "garment.obj") {
  const fs::path out = gr::test::fresh_temp_dir("golden_" + scene);
  args.insert(args.end(), {"--quiet", "--out", out.string()});
  const gr::test::CliRun run = gr::test::run_cli(args, "golden_" + scene);
  INFO(scene << ": " << run.err);
  REQUIRE(run.exit_code == 0);
  const std::string digest = gr::sha256_of_file((out / written).string());
  if (std::getenv("GR_UPDATE_GOLDEN")) record_digest(scene, digest);
  const std::map<std::string, std::string> digests = recorded_digests();
  const auto recorded = digests.find(scene);
  REQUIRE(recorded != digests.end());
  CHECK(digest == recorded->second);
}

}  // namespace

TEST_CASE("golden bytes: the bundled scene", "[cli][golden]") {
  const std::string scene = "scenes/dress_form/";
  check_golden("dress_form",
               {"retarget", "--garment", gr::test::project_file(scene + "garment.obj"), "--avatar",
                gr::test::project_file(scene + "avatar.obj"), "--no-fit",
                gr::test::project_file(scene + "no-fit.txt")});
}

TEST_CASE("golden bytes: the shared scenes", "[cli][golden]") {
  const auto data = [](const std::string& relative) { return gr::test::shared_data(relative); };
  check_golden("foxgirl_skirt",
               {"retarget", "--skirt", "--garment", data("garments/skirt/garment.obj"), "--no-fit",
                data("garments/skirt/no-fit.txt"), "--source-skeleton",
                data("garments/skirt/skeleton.obj"), "--avatar", data("avatars/foxgirl/avatar.obj"),
                "--target-skeleton", data("avatars/foxgirl/skeleton.obj")});
  check_golden("goblin_puffer",
               {"retarget", "--garment", data("garments/puffer/garment.obj"), "--no-fit",
                data("garments/puffer/no-fit.txt"), "--source-skeleton",
                data("garments/puffer/skeleton.obj"), "--avatar", data("avatars/goblin/avatar.obj"),
                "--target-skeleton", data("avatars/goblin/skeleton.obj"), "--skin-weights",
                data("avatars/goblin/skin.txt")});
}

TEST_CASE("golden bytes: skeleton-free family scenes", "[cli][golden]") {
  // A cap, a ring and a band, in another frame and units than the canonical one.
  const gr::SkeletonFreeVariant moved{12, 0.0, 40.0, 37.0, gr::Vector3d(5.0, -3.0, 2.0)};
  for (const gr::SkeletonFreeFamily family :
       {gr::SkeletonFreeFamily::kPatchSphere, gr::SkeletonFreeFamily::kPatchTorus,
        gr::SkeletonFreeFamily::kSleeveSphere}) {
    const gr::SkeletonFreeScene scene = gr::make_skeleton_free_scene(family, moved);
    const std::string name = std::string("skeleton_free_") + gr::to_string(family);
    const fs::path dir = gr::test::fresh_temp_dir("golden_input_" + name);
    gr::write_obj((dir / "garment.obj").string(), scene.garment);
    gr::write_obj((dir / "avatar.obj").string(), scene.avatar);
    check_golden(name, {"retarget", "--garment", (dir / "garment.obj").string(), "--avatar",
                        (dir / "avatar.obj").string()});
  }
}

TEST_CASE("golden bytes: a production GLB garment", "[cli][golden]") {
  // Skinned glTF in and out: the pose step, the skin written with the avatar's joints.
  const auto real = [](const std::string& name) { return gr::test::shared_data("real/" + name); };
  check_golden(
      "production_trousers_glb",
      {"retarget", "--garment", real("male-outfit.glb"), "--garment-mesh", "Wolf3D_Outfit_Bottom",
       "--avatar", real("female-full-body.glb"), "--avatar-mesh", "body.001"},
      "garment.glb");
}
