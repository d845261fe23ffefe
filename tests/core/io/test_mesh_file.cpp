#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include <catch2/catch.hpp>

#include "core/common/errors.hpp"
#include "core/io/mesh_file.hpp"
#include "core/io/obj_document.hpp"
#include "core/mesh/primitives.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;

namespace {

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

gr::TriangleMesh one_triangle() {
  gr::TriangleMesh mesh;
  mesh.vertices.resize(3, 3);
  mesh.vertices << 0.0, 0.0, 0.0, 1.0, -0.0, 0.1, 1.0 / 3.0, 2e-300, -1.5e10;
  mesh.faces.resize(1, 3);
  mesh.faces << 0, 1, 2;
  return mesh;
}

}  // namespace

TEST_CASE("write_obj of a mesh writes v and f lines in full precision", "[io][obj][mesh_file]") {
  const auto dir = gr::test::fresh_temp_dir("mesh_file_bytes");
  const fs::path path = dir / "triangle.obj";
  gr::write_obj(path.string(), one_triangle());
  CHECK(read_bytes(path) ==
        "v 0 0 0\n"
        "v 1 -0 0.10000000000000001\n"
        "v 0.33333333333333331 2.0000000000000001e-300 -15000000000\n"
        "f 1 2 3\n");
  // Nothing but the file is left in the folder (no temporary).
  CHECK(std::distance(fs::directory_iterator(dir), {}) == 1);
}

TEST_CASE("write_obj of a mesh reads back as the same doubles and faces", "[io][obj][mesh_file]") {
  const auto dir = gr::test::fresh_temp_dir("mesh_file_round_trip");
  gr::TriangleMesh mesh = gr::icosphere(2, 0.93, gr::Vector3d(0.1, -1e-7, 3.0));
  const int degenerate = GENERATE(0, 1);
  CAPTURE(degenerate);
  if (degenerate) {  // a face on a repeated vertex is written as it is
    mesh.faces.conservativeResize(mesh.faces.rows() + 1, 3);
    mesh.faces.row(mesh.faces.rows() - 1) << 5, 5, 6;
  }
  const std::string path = (dir / "mesh.obj").string();
  gr::write_obj(path, mesh);
  const gr::ObjDocument read = gr::read_obj(path);
  REQUIRE(read.positions.rows() == mesh.vertices.rows());
  CHECK((read.positions.array() == mesh.vertices.array()).all());
  REQUIRE(read.faces.size() == static_cast<std::size_t>(mesh.faces.rows()));
  for (std::size_t f = 0; f < read.faces.size(); ++f)
    for (std::size_t k = 0; k < 3; ++k) {
      CHECK(read.faces[f][k].position ==
            mesh.faces(static_cast<Eigen::Index>(f), static_cast<Eigen::Index>(k)));
      CHECK(read.faces[f][k].texcoord == -1);
      CHECK(read.faces[f][k].normal == -1);
    }
  CHECK(read.normals.rows() == 0);
  CHECK(read.statements.empty());
  CHECK(read.warnings.empty());
}

TEST_CASE("write_obj of a mesh numbers as the ObjDocument writer does", "[io][obj][mesh_file]") {
  const auto dir = gr::test::fresh_temp_dir("mesh_file_like_document");
  const gr::TriangleMesh mesh = gr::uv_sphere(0.37, gr::Vector3d(1e-3, 2.0, -7.0), 5, 7);
  const std::string plain = (dir / "plain.obj").string();
  gr::write_obj(plain, mesh);
  gr::ObjDocument document = gr::read_obj(plain);
  const std::string through_document = (dir / "document.obj").string();
  gr::write_obj(through_document, document, document.positions);
  // The document writer adds its header line; the v and f lines are the same bytes.
  const std::string text = read_bytes(through_document);
  CHECK(text.substr(text.find('\n') + 1) == read_bytes(plain));
}

TEST_CASE("write_obj of a mesh refuses malformed meshes and unwritable paths",
          "[io][obj][mesh_file]") {
  const auto dir = gr::test::fresh_temp_dir("mesh_file_errors");
  SECTION("a folder that does not exist") {
    const fs::path path = dir / "missing" / "mesh.obj";
    CHECK_THROWS_AS(gr::write_obj(path.string(), one_triangle()), gr::OutputError);
    CHECK_FALSE(fs::exists(path));
  }
  SECTION("a path that is a folder") {
    fs::create_directories(dir / "taken.obj" / "inside");
    CHECK_THROWS_AS(gr::write_obj((dir / "taken.obj").string(), one_triangle()), gr::OutputError);
    CHECK(fs::is_directory(dir / "taken.obj" / "inside"));
  }
  SECTION("a folder that is a file") {
    std::ofstream(dir / "file") << "not a folder\n";
    CHECK_THROWS_AS(gr::write_obj((dir / "file" / "mesh.obj").string(), one_triangle()),
                    gr::OutputError);
  }
  SECTION("a non-finite coordinate or a face index out of range") {
    for (int fault = 0; fault < 4; ++fault) {
      CAPTURE(fault);
      gr::TriangleMesh mesh = one_triangle();
      if (fault == 0) mesh.vertices(1, 2) = std::numeric_limits<double>::quiet_NaN();
      if (fault == 1) mesh.vertices(2, 0) = -std::numeric_limits<double>::infinity();
      if (fault == 2) mesh.faces(0, 1) = 3;
      if (fault == 3) mesh.faces(0, 2) = -1;
      const fs::path path = dir / "malformed.obj";
      CHECK_THROWS_AS(gr::write_obj(path.string(), mesh), std::invalid_argument);
      CHECK_FALSE(fs::exists(path));
    }
  }
  // Nothing is left behind by any failure.
  for (const auto& entry : fs::directory_iterator(dir))
    CHECK(entry.path().filename().string().rfind(".", 0) != 0);
}
