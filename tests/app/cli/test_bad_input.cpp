#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "core/io/mesh_file.hpp"
#include "core/io/obj_document.hpp"
#include "retarget/extremes_support.hpp"
#include "retarget/outcome.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;

namespace {

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

/// Files the cases below refer to, made once: "{G}" and "{A}" stand for the bundled
/// garment and avatar, "{D}" for this folder, "{M}" for the committed malformed corpus,
/// "{S}" for a shared skeleton.
const fs::path& bad_input_dir() {
  static const fs::path dir = [] {
    const fs::path dir = gr::test::fresh_temp_dir("bad_input");
    const std::string skeleton = gr::test::shared_data("garments/skirt/skeleton.obj");

    const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    write_text(dir / "no_faces.obj", tri);
    write_text(dir / "one_vertex_face.obj", tri + "f 1\n");
    write_text(dir / "garbage.obj", std::string("\x7f"
                                                "ELF\x02\x01\x01\x00\x00\x00 binary",
                                                20));
    write_text(dir / "uv_nan.obj", tri + "vt nan 0\nf 1/1 2/1 3/1\n");
    write_text(dir / "skeleton_short.obj", "v 0 0 0\nv 0 0 1\nv 0 1 1\nl 1 2\nl 2 3\n");
    std::string moved_bones;
    {
      std::ifstream in(skeleton);
      for (std::string line; std::getline(in, line);)
        moved_bones += (line == "l 1 2" ? std::string("l 1 3") : line) + "\n";
    }
    write_text(dir / "skeleton_other_bones.obj", moved_bones);
    write_text(dir / "a_file", "not a folder\n");

    // A small scene: a UV sphere avatar and flat patches (4×4 squares of 1/4) around it.
    gr::write_obj((dir / "sphere.obj").string(), gr::test::uv_sphere(16, 9));
    const gr::TriangleMesh patch = gr::test::flat_patch(4, 0.25, 0.9375);
    std::string quads;
    for (Eigen::Index v = 0; v < patch.vertices.rows(); ++v)
      quads += fmt::format("v {} {} {}\n", patch.vertices(v, 0), patch.vertices(v, 1),
                           patch.vertices(v, 2));
    // Squares as quads, except the last two of the first row, one hexagon whose fan from
    // its first corner has no collinear triple.
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) {
        const int a = j * 5 + i + 1, b = a + 1, c = a + 5, d = c + 1;
        if (j == 0 && i == 2) {
          quads += fmt::format("f {} {} {} {} {} {}\n", b, b + 1, d + 1, d, c, a);
          ++i;
          continue;
        }
        quads += fmt::format("f {} {} {} {}\n", a, b, d, c);
      }
    write_text(dir / "quads.obj", quads);
    // A patch through the sphere's centre: no erosion frees it.
    gr::write_obj((dir / "through_centre.obj").string(), gr::test::flat_patch(4, 0.75, 0.0));
    // Two patches crossing each other above the sphere: the garment meets itself.
    gr::TriangleMesh crossing = gr::test::flat_patch(2, 0.5, 1.5);
    gr::TriangleMesh upright = crossing;
    upright.vertices.col(2).swap(upright.vertices.col(0));
    upright.vertices.col(0).array() -= 1.5;  // the plane x = 0, z from 1.125 to 2.125
    upright.vertices.col(2).array() += 1.625;
    crossing.vertices.conservativeResize(18, 3);
    crossing.vertices.bottomRows(9) = upright.vertices;
    crossing.faces.conservativeResize(16, 3);
    crossing.faces.bottomRows(8) = upright.faces.array() + 9;
    gr::write_obj((dir / "self_crossing.obj").string(), crossing);
    return dir;
  }();
  return dir;
}

/// Runs `retarget` with `case_args` and checks the single error line, the exit code and
/// that no output file was left.
void check_bad_input(std::vector<std::string> case_args, int exit_code,
                     const std::string& message) {
  const fs::path dir = bad_input_dir();
  const std::string garment = gr::test::project_file("scenes/dress_form/garment.obj");
  const std::string avatar = gr::test::project_file("scenes/dress_form/avatar.obj");
  const std::string malformed = gr::test::project_file("tests/data/malformed");
  const std::string skeleton = gr::test::shared_data("garments/skirt/skeleton.obj");
  std::vector<std::string> args = {"retarget"};
  bool has_out = false;
  for (std::string a : case_args) {
    for (const auto& [key, value] : {std::pair<std::string, std::string>{"{G}", garment},
                                     {"{A}", avatar},
                                     {"{D}", dir.string()},
                                     {"{M}", malformed},
                                     {"{S}", skeleton}}) {
      const auto at = a.find(key);
      if (at != std::string::npos) a.replace(at, key.size(), value);
    }
    has_out |= a == "--out";
    args.push_back(a);
  }
  const fs::path out = dir / "out";
  if (!has_out) {
    args.push_back("--out");
    args.push_back(out.string());
  }
  const gr::test::CliRun run = gr::test::run_cli(args, "bad_input");
  CAPTURE(run.err, run.out);
  CHECK(run.exit_code == exit_code);
  const auto lines = gr::test::lines_of(run.err);
  REQUIRE(lines.size() == 1);
  CHECK_THAT(lines[0], Catch::StartsWith("garment-retarget: error: "));
  CHECK_THAT(lines[0], Catch::Contains(message));
  CHECK_FALSE(fs::exists(out / "garment.obj"));
  CHECK_FALSE(fs::exists(out / "certificate.json"));
}

}  // namespace

TEST_CASE("bad input: missing garment", "[cli][errors]") {
  check_bad_input({"--garment", "{D}/nope.obj", "--avatar", "{A}"}, 2, "cannot open file");
}

TEST_CASE("bad input: missing avatar", "[cli][errors]") {
  check_bad_input({"--garment", "{G}", "--avatar", "{D}/nope.obj"}, 2, "cannot open file");
}

TEST_CASE("bad input: empty garment", "[cli][errors]") {
  check_bad_input({"--garment", "{M}/empty.obj", "--avatar", "{A}"}, 2, "file is empty");
}

TEST_CASE("bad input: blank avatar", "[cli][errors]") {
  check_bad_input({"--garment", "{G}", "--avatar", "{M}/blank.obj"}, 2, "file is empty");
}

TEST_CASE("bad input: binary garment", "[cli][errors]") {
  check_bad_input({"--garment", "{M}/binary.obj", "--avatar", "{A}"}, 2, "binary data");
}

TEST_CASE("bad input: binary garbage avatar", "[cli][errors]") {
  check_bad_input({"--garment", "{G}", "--avatar", "{D}/garbage.obj"}, 2, "binary data");
}

TEST_CASE("bad input: truncated OBJ", "[cli][errors]") {
  check_bad_input({"--garment", "{M}/truncated_vertex.obj", "--avatar", "{A}"}, 2,
                  "truncated_vertex.obj:5: vertex needs three coordinates");
}

TEST_CASE("bad input: NaN coordinate", "[cli][errors]") {
  check_bad_input({"--garment", "{M}/nan_coordinate.obj", "--avatar", "{A}"}, 2,
                  "nan_coordinate.obj:2: non-finite number");
}

TEST_CASE("bad input: inf coordinate", "[cli][errors]") {
  check_bad_input({"--garment", "{G}", "--avatar", "{M}/inf_coordinate.obj"}, 2,
                  "inf_coordinate.obj:3: non-finite number");
}

TEST_CASE("bad input: NaN texture coordinate", "[cli][errors]") {
  check_bad_input({"--garment", "{D}/uv_nan.obj", "--avatar", "{A}"}, 2,
                  "uv_nan.obj:4: non-finite number");
}

TEST_CASE("bad input: malformed number", "[cli][errors]") {
  check_bad_input({"--garment", "{M}/malformed_number.obj", "--avatar", "{A}"}, 2,
                  "malformed number '1x'");
}

TEST_CASE("bad input: index out of range", "[cli][errors]") {
  check_bad_input({"--garment", "{M}/index_out_of_range.obj", "--avatar", "{A}"}, 2,
                  "vertex index 4 out of range");
}

TEST_CASE("bad input: index zero", "[cli][errors]") {
  check_bad_input({"--garment", "{M}/index_zero.obj", "--avatar", "{A}"}, 2, "vertex index 0");
}

TEST_CASE("bad input: negative index out of range", "[cli][errors]") {
  check_bad_input({"--garment", "{M}/negative_index_out_of_range.obj", "--avatar", "{A}"}, 2,
                  "vertex index -4 out of range");
}

TEST_CASE("bad input: face with one vertex", "[cli][errors]") {
  check_bad_input({"--garment", "{D}/one_vertex_face.obj", "--avatar", "{A}"}, 2,
                  "face with 1 vertices");
}

TEST_CASE("bad input: face with two vertices", "[cli][errors]") {
  check_bad_input({"--garment", "{M}/face_two_vertices.obj", "--avatar", "{A}"}, 2,
                  "face with 2 vertices");
}

TEST_CASE("bad input: garment with no faces", "[cli][errors]") {
  check_bad_input({"--garment", "{D}/no_faces.obj", "--avatar", "{A}"}, 2,
                  "garment has no (non-degenerate) triangle");
}

TEST_CASE("A non-manifold garment is split for the solver and welded back", "[cli][repairs]") {
  const fs::path dir = bad_input_dir();
  // A patch over the sphere with two fins on one of its inner edges: three and four faces
  // share the edge.
  gr::TriangleMesh patch = gr::test::flat_patch(4, 0.25, 1.5);
  const int a = 6, b = 12;  // an inner diagonal (faces a, b, d of the grid)
  const Eigen::Index n = patch.vertices.rows();
  patch.vertices.conservativeResize(n + 2, 3);
  patch.vertices.row(n) = 0.5 * (patch.vertices.row(a) + patch.vertices.row(b));
  patch.vertices(n, 2) += 0.2;
  patch.vertices.row(n + 1) = patch.vertices.row(n);
  patch.vertices(n + 1, 2) += 0.15;
  patch.vertices(n + 1, 0) += 0.1;
  const Eigen::Index f = patch.faces.rows();
  patch.faces.conservativeResize(f + 2, 3);
  patch.faces.row(f) << a, b, static_cast<int>(n);
  patch.faces.row(f + 1) << b, a, static_cast<int>(n + 1);
  gr::write_obj((dir / "fins.obj").string(), patch);
  const fs::path out = dir / "fins_out";
  const gr::test::CliRun run =
      gr::test::run_cli({"retarget", "--garment", (dir / "fins.obj").string(), "--avatar",
                         (dir / "sphere.obj").string(), "--out", out.string(), "--quality", "fast",
                         "--voxel-size", "0.05"},
                        "nonmanifold_fins");
  CAPTURE(run.out, run.err);
  REQUIRE(run.exit_code == gr::to_exit_code(gr::Outcome::kCertified));
  CHECK_THAT(run.err, Catch::Contains("1 edges shared by more than two faces were split"));
  const auto report = nlohmann::json::parse(gr::test::read_text(out / "report.json"));
  CHECK(report["split_non_manifold_edges"]["edges"] == 1);
  CHECK(report["split_non_manifold_edges"]["vertex_copies"] == 4);
  // The written file keeps the input's vertices and faces: the copies are welded back.
  const gr::ObjDocument written = gr::read_obj((out / "garment.obj").string());
  CHECK(written.positions.rows() == patch.vertices.rows());
  CHECK(written.faces.size() == static_cast<std::size_t>(patch.faces.rows()));
  // Still a fan of four faces on the edge, and the fins still stand off the patch.
  CHECK((written.positions.row(n) - written.positions.row(a)).norm() > 0.05);
}

TEST_CASE("bad input: skeletons with different joint counts", "[cli][errors]") {
  check_bad_input({"--garment", "{G}", "--avatar", "{A}", "--source-skeleton", "{S}",
                   "--target-skeleton", "{D}/skeleton_short.obj"},
                  2, "3 joints, source skeleton has 15");
}

TEST_CASE("bad input: skeletons with different bones", "[cli][errors]") {
  check_bad_input({"--garment", "{G}", "--avatar", "{A}", "--source-skeleton", "{S}",
                   "--target-skeleton", "{D}/skeleton_other_bones.obj"},
                  2, "bones differ");
}

TEST_CASE("bad input: source skeleton alone", "[cli][errors]") {
  check_bad_input({"--garment", "{G}", "--avatar", "{A}", "--source-skeleton", "{S}"}, 2,
                  "requires");
}

TEST_CASE("bad input: skeleton without bones", "[cli][errors]") {
  check_bad_input({"--garment", "{G}", "--avatar", "{A}", "--source-skeleton",
                   "{M}/skeleton_no_bones.obj", "--target-skeleton", "{S}"},
                  2, "no bones");
}

TEST_CASE("bad input: skin weights of the wrong shape", "[cli][errors]") {
  check_bad_input({"--garment", "{G}", "--avatar", "{A}", "--source-skeleton", "{S}",
                   "--target-skeleton", "{S}", "--skin-weights", "{M}/skin_ragged.txt"},
                  2, "columns, expected one per avatar vertex");
}

TEST_CASE("bad input: skin weights without skeletons", "[cli][errors]") {
  check_bad_input({"--garment", "{G}", "--avatar", "{A}", "--skin-weights", "{M}/skin_ragged.txt"},
                  2, "requires");
}

TEST_CASE("bad input: negative no-fit id", "[cli][errors]") {
  check_bad_input({"--garment", "{G}", "--avatar", "{A}", "--no-fit", "{M}/nofit_negative.txt"}, 2,
                  "negative vertex id -3");
}

TEST_CASE("bad input: no-fit id out of range", "[cli][errors]") {
  check_bad_input({"--garment", "{M}/index_zero.obj", "--avatar", "{A}", "--no-fit",
                   "{M}/nofit_out_of_range.txt"},
                  2, "vertex index 0");
}

TEST_CASE("bad input: no-fit garbage", "[cli][errors]") {
  check_bad_input({"--garment", "{G}", "--avatar", "{A}", "--no-fit", "{M}/nofit_garbage.txt"}, 2,
                  "malformed integer 'two'");
}

TEST_CASE("bad input: unknown option", "[cli][errors]") {
  check_bad_input({"--garment", "{G}", "--avatar", "{A}", "--frobnicate"}, 2, "frobnicate");
}

TEST_CASE("bad input: unknown quality", "[cli][errors]") {
  check_bad_input({"--garment", "{G}", "--avatar", "{A}", "--quality", "best"}, 2, "best");
}

TEST_CASE("bad input: output folder is a file", "[cli][errors]") {
  check_bad_input({"--garment", "{G}", "--avatar", "{A}", "--out", "{D}/a_file/out"}, 5,
                  "cannot create output folder");
}

TEST_CASE("bad input: output folder under /proc cannot be created", "[cli][errors]") {
  check_bad_input({"--garment", "{G}", "--avatar", "{A}", "--out", "/proc/gr_no_such_folder/out"},
                  5, "/proc/gr_no_such_folder/out: cannot create output folder");
}

TEST_CASE("A garment that crosses itself as given is retargeted with its crossings kept",
          "[cli][inherited]") {
  const fs::path dir = bad_input_dir();
  const fs::path out = dir / "crossing_out";
  const std::string garment = (dir / "self_crossing.obj").string();
  const gr::test::CliRun run = gr::test::run_cli(
      {"retarget", "--garment", garment, "--avatar", (dir / "sphere.obj").string(), "--out",
       out.string(), "--quality", "fast", "--voxel-size", "0.05"},
      "inherited_crossing");
  CAPTURE(run.err, run.out);
  REQUIRE(run.exit_code == gr::to_exit_code(gr::Outcome::kCertified));
  CHECK_THAT(run.out,
             Catch::Contains("0 self intersections (and") && Catch::Contains("inherited)"));
  const auto report = nlohmann::json::parse(gr::test::read_text(out / "report.json"));
  const int pairs = report["inherited_crossings"]["pairs"].get<int>();
  CHECK(pairs > 0);
  CHECK(report["inherited_crossings"]["tangles"] == 1);
  CHECK(report["inherited_crossings"]["face_pairs"].size() == static_cast<std::size_t>(pairs));
  CHECK_THAT(report["warnings"].dump(), Catch::Contains("crosses itself as given"));
  const auto certificate = nlohmann::json::parse(gr::test::read_text(out / "certificate.json"));
  CHECK(certificate["certified"] == true);
  CHECK(certificate["counts"]["garment_self_intersections"] == 0);
  CHECK(certificate["counts"]["inherited_self_intersections"].get<int>() ==
        report["inherited_crossings"]["still_crossing"].get<int>());

  // validate alone fails the output on its crossings, and counts them apart with --source.
  const std::vector<std::string> validate = {"validate", "--garment",
                                             (out / "garment.obj").string(), "--avatar",
                                             (dir / "sphere.obj").string()};
  CHECK(gr::test::run_cli(validate, "inherited_validate").exit_code ==
        gr::to_exit_code(gr::Outcome::kNotCertified));
  std::vector<std::string> with_source = validate;
  with_source.insert(with_source.end(), {"--source", garment, "--shape-check", "off"});
  const gr::test::CliRun split = gr::test::run_cli(with_source, "inherited_validate_source");
  CAPTURE(split.out);
  CHECK(split.exit_code == gr::to_exit_code(gr::Outcome::kCertified));
  CHECK_THAT(split.out, Catch::Contains("0 self") && Catch::Contains("inherited self pairs"));
}

TEST_CASE("bad input: quads and n-gons are triangulated with a warning and the run proceeds",
          "[cli][errors]") {
  const fs::path dir = bad_input_dir();
  const fs::path out = dir / "quads_out";
  const gr::test::CliRun run =
      gr::test::run_cli({"retarget", "--garment", (dir / "quads.obj").string(), "--avatar",
                         (dir / "sphere.obj").string(), "--out", out.string(), "--quality", "fast",
                         "--voxel-size", "0.05", "--eps-tol", "1e-2"},
                        "bad_input_quads");
  CAPTURE(run.err, run.out);
  CHECK(run.exit_code == gr::to_exit_code(gr::Outcome::kCertified));
  CHECK_THAT(run.out, Catch::StartsWith("certified"));
  int warnings = 0;
  for (const auto& line : gr::test::lines_of(run.err))
    if (line.find("warning") != std::string::npos &&
        line.find("no --source-body") == std::string::npos) {  // the tight fit's warning
      ++warnings;
      CHECK_THAT(line, Catch::Contains("quads.obj") &&
                           Catch::Contains("15 polygons with more than 3 vertices triangulated"));
    }
  CHECK(warnings == 1);
  CHECK(fs::exists(out / "garment.obj"));
  CHECK(gr::read_obj((out / "garment.obj").string()).faces.size() == 32);
}

TEST_CASE("bad input: garment through the avatar's core, no shrink frees it", "[cli][errors]") {
  const fs::path dir = bad_input_dir();
  const fs::path out = dir / "no_shrink_out";
  const gr::test::CliRun run =
      gr::test::run_cli({"retarget", "--garment", (dir / "through_centre.obj").string(), "--avatar",
                         (dir / "sphere.obj").string(), "--out", out.string(), "--quality", "fast",
                         "--voxel-size", "0.05", "--quiet"},
                        "bad_input_no_shrink");
  CAPTURE(run.err, run.out);
  CHECK(run.exit_code == gr::to_exit_code(gr::Outcome::kNoValidShrink));
  CHECK(run.err.empty());
  const auto lines = gr::test::lines_of(run.out);
  REQUIRE(lines.size() == 1);
  CHECK_THAT(lines[0],
             Catch::StartsWith("no valid shrink: ") && Catch::Contains("in the garment's frame"));
  CHECK(fs::exists(out / "report.json"));
  CHECK_FALSE(fs::exists(out / "garment.obj"));
  CHECK_FALSE(fs::exists(out / "certificate.json"));
}

TEST_CASE("bad input: a .glb that is not glTF", "[cli][errors][gltf]") {
  write_text(bad_input_dir() / "not_gltf.glb", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  check_bad_input({"--garment", "{D}/not_gltf.glb", "--avatar", "{A}"}, 2,
                  "not_gltf.glb: is not a glTF file");
}

TEST_CASE("bad input: a mesh name for an OBJ", "[cli][errors][gltf]") {
  check_bad_input({"--garment", "{G}", "--avatar", "{A}", "--avatar-mesh", "body"}, 2,
                  "--avatar-mesh is for glTF files only");
}
