#include <fstream>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "core/common/errors.hpp"
#include "core/io/mesh_file.hpp"
#include "core/io/obj_document.hpp"
#include "test_support.hpp"
#include "validate/certify/certificate.hpp"
#include "validate/report/file_digest.hpp"
#include "validate/report/marks_file.hpp"
#include "validate/report/validation_report.hpp"
#include "validate/validate_test_meshes.hpp"

using gr::test::make_mesh;
using gr::test::triangle;

namespace {

std::string write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
  return path.string();
}

std::string write_mesh(const std::filesystem::path& path, const gr::TriangleMesh& mesh) {
  gr::write_obj(path.string(), mesh);
  return path.string();
}

nlohmann::json read_json(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

const gr::TriangleMesh kAvatar =
    make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}, {{0, 1, 2}, {1, 3, 2}});

}  // namespace

TEST_CASE("certificate of a clean garment, computed from the files", "[validate][certificate]") {
  const auto dir = gr::test::fresh_temp_dir("certificate_clean");
  const std::string avatar = write_mesh(dir / "avatar.obj", kAvatar);
  const std::string garment =
      write_mesh(dir / "garment.obj", triangle({0.1, 0.1, 0.5}, {0.9, 0.1, 0.5}, {0.1, 0.9, 0.5}));
  const nlohmann::json extra = {{"parameters", {{"dhat", 0.002}}},
                                {"input_sha256", {{"garment", "abc"}}}};
  gr::ValidationOptions options;
  options.threshold = 0.6;
  const gr::Certificate c = gr::certify_garment(garment, avatar, extra, options);
  CHECK(c.certified());
  CHECK(c.json["certified"] == true);
  CHECK(c.json["kind"] == "certificate");
  CHECK(c.json["extra"]["parameters"]["dhat"] == 0.002);
  CHECK(c.json["tool"]["version"] == GR_VERSION);
  CHECK(c.json["inputs"]["garments"][0]["sha256"] == gr::sha256_of_file(garment));
  CHECK(c.json["inputs"]["avatar"]["sha256"] == gr::sha256_of_file(avatar));
  CHECK(c.json["garments"][0]["avatar_clearance"]["distance"].get<double>() == Approx(0.5));
  CHECK(c.json["counts"]["near_vertices"] == 3);
  CHECK(c.json["issues"]["num_errors"] == 0);

  const std::string path = (dir / "certificate.json").string();
  gr::write_certificate(path, c);
  const nlohmann::json written = read_json(path);
  CHECK(written["certified"] == true);
  CHECK(written["extra"] == extra);
}

TEST_CASE("certification reads the file as written, not a welded mesh", "[validate][certificate]") {
  const auto dir = gr::test::fresh_temp_dir("certificate_written");
  const std::string avatar = write_mesh(dir / "avatar.obj", kAvatar);
  // A quad written as one polygon (triangulated by the reader) hovering above the avatar,
  // and a second quad whose corner dips to touch the avatar.
  const std::string garment = write_text(dir / "garment.obj",
                                         "v 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                                         "v 0 0 2\nv 1 0 2\nv 1 1 2\nv 0.5 0.5 0\n"
                                         "f 1 2 3 4\nf 5 6 7 8\n");
  const gr::Certificate c = gr::certify_garment(garment, avatar);
  CHECK_FALSE(c.certified());
  // Faces in triangulated order: the second polygon is faces 2 and 3; only face 3 has
  // the corner at z = 0 ... (5 6 7) and (5 7 8).
  const auto& pairs = c.json["garments"][0]["avatar_intersections"]["pairs"];
  REQUIRE(pairs.size() >= 1);
  for (const auto& p : pairs) CHECK(p[0] == 3);
  CHECK(c.json["inputs"]["garments"][0]["faces"] == 4);
  CHECK(c.json["inputs"]["garments"][0]["reader_warnings"].size() == 1);
  // The corner touches the avatar on the diagonal shared by its two faces, and face 3
  // crosses the first quad (faces 0 and 1) on its way down.
  CHECK(c.json["counts"]["garment_avatar_intersections"] == 2);
  CHECK(c.json["counts"]["garment_self_intersections"] == 2);
  CHECK(c.json["issues"]["num_errors"] == 4);
}

TEST_CASE("validation of layers: each against the avatar and against each other",
          "[validate][report]") {
  const auto dir = gr::test::fresh_temp_dir("validation_layers");
  const std::string avatar = write_mesh(dir / "avatar.obj", kAvatar);
  const std::string inner =
      write_mesh(dir / "inner.obj", triangle({0.1, 0.1, 0.5}, {0.9, 0.1, 0.5}, {0.1, 0.9, 0.5}));
  const std::string outer =
      write_mesh(dir / "outer.obj", triangle({0.2, 0.2, 0.4}, {0.3, 0.2, 0.6}, {0.2, 0.3, 0.6}));
  const std::string apart =
      write_mesh(dir / "apart.obj", triangle({0.1, 0.1, 0.9}, {0.9, 0.1, 0.9}, {0.1, 0.9, 0.9}));

  const gr::Validation crossing = gr::validate_files({inner, outer}, avatar, {});
  CHECK_FALSE(crossing.result.certified());
  REQUIRE(crossing.result.garment_pairs.size() == 1);
  CHECK(crossing.result.garment_pairs[0].intersections.count == 1);
  CHECK(crossing.result.garment_pairs[0].clearance.distance == 0.0);
  const auto report = gr::validation_report(crossing);
  CHECK(report["counts"]["garment_garment_intersections"] == 1);
  CHECK(report["counts"]["garment_avatar_intersections"] == 0);
  std::size_t layer_messages = 0;
  for (const auto& message : report["issues"]["messages"])
    if (message["code"] == "GARMENT_GARMENT_INTERSECTION") {
      ++layer_messages;
      CHECK(message["severity"] == "error");
      CHECK(message["garments"] == nlohmann::ordered_json::array({0, 1}));
    }
  CHECK(layer_messages == 1);
  CHECK(gr::validation_summary(crossing).rfind("NOT certified", 0) == 0);

  const gr::Validation layered = gr::validate_files({inner, apart}, avatar, {});
  CHECK(layered.result.certified());
  CHECK(layered.result.garment_pairs[0].clearance.distance == Approx(0.4));
  CHECK(gr::validation_summary(layered).rfind("certified", 0) == 0);
}

TEST_CASE("the marks file holds exactly the offending faces", "[validate][report]") {
  const auto dir = gr::test::fresh_temp_dir("validation_marks");
  const std::string avatar = write_mesh(dir / "avatar.obj", kAvatar);
  // Face 0 pierces avatar face 0; face 1 is far away; face 2 is degenerate and far away.
  const std::string garment =
      write_mesh(dir / "garment.obj", make_mesh({{0.2, 0.2, -1},
                                                 {0.3, 0.2, 1},
                                                 {0.2, 0.3, 1},
                                                 {5, 5, 5},
                                                 {6, 5, 5},
                                                 {5, 6, 5},
                                                 {7, 7, 7},
                                                 {8, 8, 8},
                                                 {9, 9, 9}},
                                                {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}}));
  const gr::Validation v = gr::validate_files({garment}, avatar, {});
  const std::string marks = (dir / "marks.obj").string();
  gr::write_marks_obj(marks, v);
  const gr::ObjDocument doc = gr::read_obj(marks);
  CHECK(doc.faces.size() == 3);  // garment face 0, degenerate face 2, avatar face 0
  CHECK(doc.positions.rows() == 9);
  CHECK(doc.positions(0, 2) == -1.0);
  std::size_t groups = 0;
  for (const gr::ObjStatement& s : doc.statements)
    if (s.text.rfind("g ", 0) == 0) ++groups;
  CHECK(groups == 3);
}

TEST_CASE("bad input to validation is an InputError", "[validate][report]") {
  const auto dir = gr::test::fresh_temp_dir("validation_bad_input");
  const std::string avatar = write_mesh(dir / "avatar.obj", kAvatar);
  const std::string no_faces = write_text(dir / "points.obj", "v 0 0 0\nv 1 0 0\n");
  CHECK_THROWS_AS(gr::validate_files({(dir / "missing.obj").string()}, avatar, {}), gr::InputError);
  CHECK_THROWS_AS(gr::validate_files({no_faces}, avatar, {}), gr::InputError);
  CHECK_THROWS_AS(gr::validate_files({}, avatar, {}), gr::InputError);
  gr::ValidationOptions negative;
  negative.threshold = -1.0;
  CHECK_THROWS_AS(gr::validate_files({avatar}, avatar, negative), gr::InputError);
}

TEST_CASE("report lists are capped while counts stay complete", "[validate][report]") {
  const auto dir = gr::test::fresh_temp_dir("validation_capped");
  const std::string avatar = write_mesh(dir / "avatar.obj", kAvatar);
  // Two faces piercing the avatar.
  const std::string garment = write_mesh(dir / "garment.obj", make_mesh({{0.2, 0.2, -1},
                                                                         {0.3, 0.2, 1},
                                                                         {0.2, 0.3, 1},
                                                                         {0.6, 0.6, -1},
                                                                         {0.7, 0.6, 1},
                                                                         {0.6, 0.7, 1}},
                                                                        {{0, 1, 2}, {3, 4, 5}}));
  const gr::Validation v = gr::validate_files({garment}, avatar, {});
  const auto capped = gr::validation_report(v, 1);
  CHECK(capped["counts"]["garment_avatar_intersections"] == 2);
  CHECK(capped["garments"][0]["avatar_intersections"]["count"] == 2);
  CHECK(capped["garments"][0]["avatar_intersections"]["pairs"].size() == 1);
  CHECK(capped["issues"]["num_errors"] == 2);
  CHECK(capped["issues"]["truncated"] == true);
  const auto full = gr::validation_report(v, 10);
  CHECK(full["garments"][0]["avatar_intersections"]["pairs"].size() == 2);
  CHECK(full["issues"]["truncated"] == false);
}
