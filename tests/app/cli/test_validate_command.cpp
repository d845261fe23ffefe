#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "core/io/obj_document.hpp"
#include "test_support.hpp"
#include "validate/report/file_digest.hpp"

namespace {

struct Run {
  int exit_code = -1;
  std::string out;
  std::string err;
};

std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::size_t line_count(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

/// Runs `garment-retarget validate <arguments>` with stdout and stderr captured.
Run validate(const std::filesystem::path& dir, const std::string& arguments) {
  const auto out = dir / "stdout.txt";
  const auto err = dir / "stderr.txt";
  const std::string command = std::string("\"") + GR_CLI_PATH + "\" validate " + arguments +
                              " >\"" + out.string() + "\" 2>\"" + err.string() + "\"";
  const int status = std::system(command.c_str());
  REQUIRE(WIFEXITED(status));
  return {WEXITSTATUS(status), slurp(out), slurp(err)};
}

std::string write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
  return "\"" + path.string() + "\"";
}

// The avatar: a unit square at z = 0. Garments: triangles at given heights; "pierce" goes
// through the square.
const char* kAvatar = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n";
const char* kAbove = "v 0.1 0.1 0.5\nv 0.9 0.1 0.5\nv 0.1 0.9 0.5\nf 1 2 3\n";
const char* kHigher = "v 0.1 0.1 0.8\nv 0.9 0.1 0.8\nv 0.1 0.9 0.8\nf 1 2 3\n";
const char* kPierce =
    "v 5 5 5\nv 6 5 5\nv 5 6 5\nv 0.2 0.2 -1\nv 0.3 0.2 1\nv 0.2 0.3 1\nf 1 2 3\nf 4 5 6\n";

}  // namespace

TEST_CASE("validate: a clean garment exits 0 with a one-line summary", "[tools][cli][validate]") {
  const auto dir = gr::test::fresh_temp_dir("cli_validate_clean");
  const std::string avatar = write_text(dir / "avatar.obj", kAvatar);
  const std::string garment = write_text(dir / "garment.obj", kAbove);
  const Run run =
      validate(dir, "--garment " + garment + " --avatar " + avatar +
                        " --threshold 0.6 --report \"" + (dir / "report.json").string() + "\"");
  CHECK(run.exit_code == 0);
  CHECK(line_count(run.out) == 1);
  CHECK(run.out.rfind("certified:", 0) == 0);
  CHECK(run.err.empty());
  const auto report = nlohmann::json::parse(slurp(dir / "report.json"));
  CHECK(report["certified"] == true);
  CHECK(report["schema"] == "garment-retarget/validation-report/1");
  CHECK(report["garments"][0]["avatar_clearance"]["distance"].get<double>() == Approx(0.5));
  CHECK(report["garments"][0]["near_vertices"]["count"] == 3);
  CHECK(report["parameters"]["threshold"] == 0.6);
}

TEST_CASE("validate: intersections exit 1, with report and marks", "[tools][cli][validate]") {
  const auto dir = gr::test::fresh_temp_dir("cli_validate_hit");
  const std::string avatar = write_text(dir / "avatar.obj", kAvatar);
  const std::string garment = write_text(dir / "garment.obj", kPierce);
  const auto report_path = dir / "report.json";
  const auto marks_path = dir / "marks.obj";
  const Run run =
      validate(dir, "--garment " + garment + " --avatar " + avatar + " --report \"" +
                        report_path.string() + "\" --marks \"" + marks_path.string() + "\"");
  CHECK(run.exit_code == 1);
  CHECK(line_count(run.out) == 1);
  CHECK(run.out.rfind("NOT certified", 0) == 0);

  const auto report = nlohmann::json::parse(slurp(report_path));
  CHECK(report["certified"] == false);
  CHECK(report["tool"]["version"] == GR_VERSION);
  CHECK(report["inputs"]["garments"][0]["sha256"] ==
        gr::sha256_of_file((dir / "garment.obj").string()));
  CHECK(report["inputs"]["avatar"]["sha256"] == gr::sha256_of_file((dir / "avatar.obj").string()));
  CHECK(report["counts"]["garment_avatar_intersections"] == 1);
  CHECK(report["garments"][0]["avatar_intersections"]["pairs"] == nlohmann::json::array({{1, 0}}));
  CHECK(report["issues"]["num_errors"] == 1);
  CHECK(report["issues"]["messages"][0]["code"] == "GARMENT_AVATAR_INTERSECTION");
  CHECK(report["issues"]["messages"][0]["severity"] == "error");

  const gr::ObjDocument marks = gr::read_obj(marks_path.string());
  CHECK(marks.faces.size() == 2);  // garment face 1 and avatar face 0
  CHECK(marks.positions.rows() == 6);
}

TEST_CASE("validate: layers are checked against each other", "[tools][cli][validate]") {
  const auto dir = gr::test::fresh_temp_dir("cli_validate_layers");
  const std::string avatar = write_text(dir / "avatar.obj", kAvatar);
  const std::string inner = write_text(dir / "inner.obj", kAbove);
  const std::string outer = write_text(dir / "outer.obj", kHigher);
  CHECK(validate(dir, "--garment " + inner + " --garment " + outer + " --avatar " + avatar)
            .exit_code == 0);
  CHECK(validate(dir, "--garment " + inner + " --garment " + inner + " --avatar " + avatar)
            .exit_code == 1);
}

TEST_CASE("validate: bad input exits 2 with one error line", "[tools][cli][validate]") {
  const auto dir = gr::test::fresh_temp_dir("cli_validate_bad");
  const std::string avatar = write_text(dir / "avatar.obj", kAvatar);
  const std::string garment = write_text(dir / "garment.obj", kAbove);
  SECTION("missing garment file") {
    const Run run =
        validate(dir, "--garment \"" + (dir / "missing.obj").string() + "\" --avatar " + avatar);
    CHECK(run.exit_code == 2);
    CHECK(line_count(run.err) == 1);
    CHECK(run.err.find("missing.obj") != std::string::npos);
    CHECK(run.out.empty());
  }
  SECTION("malformed avatar file") {
    const std::string broken = write_text(dir / "broken.obj", "v 0 0\nf 1 2 3\n");
    const Run run = validate(dir, "--garment " + garment + " --avatar " + broken);
    CHECK(run.exit_code == 2);
    CHECK(line_count(run.err) == 1);
  }
  SECTION("no avatar") { CHECK(validate(dir, "--garment " + garment).exit_code == 2); }
  SECTION("negative threshold") {
    CHECK(validate(dir, "--garment " + garment + " --avatar " + avatar + " --threshold -1")
              .exit_code == 2);
  }
  SECTION("nothing written when the input is bad") {
    validate(dir, "--garment \"" + (dir / "missing.obj").string() + "\" --avatar " + avatar +
                      " --report \"" + (dir / "report.json").string() + "\"");
    CHECK_FALSE(std::filesystem::exists(dir / "report.json"));
  }
}

namespace {

/// The bundled scene's garment with every `v` line mapped by an affine map about
/// `centre`: scaled by `scale`, then its y squeezed by `squeeze` (an affine map keeps it
/// free of self-intersection, so only the shape check can object).
std::string crushed_copy(const std::filesystem::path& path, const std::string& source, double scale,
                         double squeeze) {
  std::istringstream in(slurp(source));
  std::ostringstream out;
  std::string line;
  const double centre[3] = {0.35, 0.87, -0.2};
  while (std::getline(in, line)) {
    if (line.rfind("v ", 0) != 0) {
      out << line << '\n';
      continue;
    }
    std::istringstream fields(line.substr(2));
    double p[3];
    fields >> p[0] >> p[1] >> p[2];
    for (int k = 0; k < 3; ++k)
      p[k] = centre[k] + scale * (k == 1 ? squeeze : 1.0) * (p[k] - centre[k]);
    out << "v " << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
  }
  return write_text(path, out.str());
}

}  // namespace

TEST_CASE("validate --source: a crushed garment exits 7, an unchanged one 0",
          "[tools][cli][validate][shape]") {
  const auto dir = gr::test::fresh_temp_dir("cli_validate_shape");
  const std::string source = gr::test::project_file("scenes/dress_form/garment.obj");
  const std::string avatar = write_text(dir / "avatar.obj", kAvatar);  // clear of the garment
  const std::string crushed = crushed_copy(dir / "crushed.obj", source, 0.3, 0.3);
  const std::string quoted_source = "\"" + source + "\"";

  const Run same =
      validate(dir, "--garment " + quoted_source + " --avatar " + avatar + " --source " +
                        quoted_source + " --report \"" + (dir / "same.json").string() + "\"");
  CHECK(same.exit_code == 0);
  const auto same_report = nlohmann::json::parse(slurp(dir / "same.json"));
  CHECK(same_report["garments"][0]["shape"]["scale"] == 1.0);
  CHECK(same_report["garments"][0]["shape"]["within_thresholds"] == true);

  const Run flagged =
      validate(dir, "--garment " + crushed + " --avatar " + avatar + " --source " + quoted_source +
                        " --report \"" + (dir / "crushed.json").string() + "\"");
  CHECK(flagged.exit_code == 7);
  CHECK(flagged.out.find("SHAPE CHANGED") != std::string::npos);
  CHECK(flagged.err.find("scale") != std::string::npos);
  const auto report = nlohmann::json::parse(slurp(dir / "crushed.json"));
  CHECK(report["certified"] == true);
  const auto& shape = report["garments"][0]["shape"];
  CHECK(shape["scale"].get<double>() < 0.3);
  CHECK(shape["mean_edge_change"].get<double>() > 0.25);
  CHECK(shape["within_thresholds"] == false);
  CHECK(shape["source"]["sha256"] == gr::sha256_of_file(source));

  const Run off = validate(dir, "--garment " + crushed + " --avatar " + avatar + " --source " +
                                    quoted_source + " --shape-check off");
  CHECK(off.exit_code == 0);

  const Run wrong =
      validate(dir, "--garment " + crushed + " --avatar " + avatar + " --source " + avatar);
  CHECK(wrong.exit_code == 2);
  CHECK(wrong.err.find("not the source") != std::string::npos);
}
