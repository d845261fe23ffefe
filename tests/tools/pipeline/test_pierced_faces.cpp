#include <filesystem>
#include <fstream>
#include <string>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "extremes_support.hpp"
#include "tools/cli/exit_codes.hpp"
#include "tools/pipeline/pierced_faces.hpp"

namespace fs = std::filesystem;
using namespace gr;

namespace {

/// A closed cube of side 2 around the origin (12 faces, outward).
TriangleMesh closed_cube() {
  TriangleMesh cube;
  cube.vertices.resize(8, 3);
  for (int i = 0; i < 8; ++i)
    cube.vertices.row(i) << (i & 1 ? 1 : -1), (i & 2 ? 1 : -1), (i & 4 ? 1 : -1);
  cube.faces.resize(12, 3);
  cube.faces << 0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2,
      4, 6, 1, 3, 5, 3, 7, 5;
  return cube;
}

/// One bone along y from -3 to 3, through the cube's bottom and top.
Skeleton vertical_bone() {
  Skeleton skeleton;
  skeleton.joints.resize(2, 3);
  skeleton.joints << 0.1, -3, 0.2, 0.1, 3, 0.2;
  skeleton.bones.resize(1, 2);
  skeleton.bones << 0, 1;
  return skeleton;
}

}  // namespace

TEST_CASE("Bones through a closed shell name its pierced faces", "[pierced]") {
  const TriangleMesh cube = closed_cube();
  const Skeleton bone = vertical_bone();
  const std::vector<FacePair> pierced = faces_pierced_by_bones(cube, bone);
  REQUIRE(pierced.size() == 2);  // one face of the bottom, one of the top
  for (const FacePair& p : pierced) CHECK(p.second == 0);
  // Open at top and bottom (a tube: without the y = -1 and y = 1 faces, rows 4 to 7),
  // nothing is pierced.
  TriangleMesh tube = cube;
  tube.faces.resize(8, 3);
  tube.faces << cube.faces.topRows(4), cube.faces.bottomRows(4);
  CHECK(faces_pierced_by_bones(tube, bone).empty());
  std::vector<int> face_to_obj(12);
  for (int f = 0; f < 12; ++f) face_to_obj[static_cast<std::size_t>(f)] = f;
  const std::string line = describe_pierced_faces(pierced, face_to_obj, bone, {"Hips", "Head"});
  CHECK_THAT(line, Catch::Contains("2 garment faces") && Catch::Contains("Hips-Head") &&
                       Catch::Contains("closed shell or cap"));
}

TEST_CASE("A capped garment over a skeleton: no valid shrink, naming the faces and bones",
          "[pierced][cli]") {
  const fs::path dir = test::fresh_temp_dir("pierced_shell");
  // A long body through a closed box: the box's caps cross it, and its bone pierces them.
  TriangleMesh body = test::uv_sphere(16, 12);
  body.vertices.col(0) *= 0.5;
  body.vertices.col(2) *= 0.5;
  body.vertices.col(1) *= 2.5;
  test::write_mesh_obj(dir / "body.obj", body);
  test::write_mesh_obj(dir / "box.obj", closed_cube());
  std::ofstream(dir / "skeleton.obj")
      << "v 0.1 -2.4 0.2\nv 0.1 0 0.2\nv 0.1 2.4 0.2\nl 1 2\nl 2 3\n";
  const fs::path out = dir / "out";
  const test::CliRun run = test::run_cli(
      {"retarget", "--garment", (dir / "box.obj").string(), "--avatar", (dir / "body.obj").string(),
       "--source-skeleton", (dir / "skeleton.obj").string(), "--target-skeleton",
       (dir / "skeleton.obj").string(), "--out", out.string(), "--quality", "fast", "--quiet"},
      "pierced_shell");
  CAPTURE(run.out, run.err);
  CHECK(run.exit_code == kExitNoValidShrink);
  CHECK_THAT(run.out, Catch::Contains("bones pass through 2 garment faces") &&
                          Catch::Contains("joint 0-joint 1") && Catch::Contains("joint 1-joint 2"));
  // The closest shrunk avatar tried is written, with the faces that still cross.
  CHECK(fs::is_regular_file(out / "closest_shrunk_avatar.obj"));
  const auto report = nlohmann::json::parse(test::read_text(out / "report.json"));
  CHECK(report["shrink_conflict"]["crossing_garment_faces"].size() >= 2);
  CHECK_FALSE(report["shrink_conflict"]["crossing_avatar_faces"].empty());
  CHECK_FALSE(fs::exists(out / "garment.obj"));
}
