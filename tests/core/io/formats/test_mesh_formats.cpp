#include <array>
#include <cctype>
#include <set>
#include <stdexcept>
#include <string>

#include <catch2/catch.hpp>

#include "core/common/errors.hpp"
#include "core/io/formats/mesh_formats.hpp"
#include "test_support.hpp"

namespace gr {

namespace {

/// A tetrahedron whose coordinates a 32-bit float holds exactly (glTF stores floats).
ObjDocument small_tetrahedron() {
  ObjDocument document;
  document.positions.resize(4, 3);
  document.positions << 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 0.0, 0.25;
  for (const auto& face : {std::array<int, 3>{0, 2, 1}, std::array<int, 3>{0, 1, 3},
                           std::array<int, 3>{0, 3, 2}, std::array<int, 3>{1, 2, 3}})
    document.faces.push_back({ObjCorner{face[0]}, ObjCorner{face[1]}, ObjCorner{face[2]}});
  return document;
}

}  // namespace

TEST_CASE("every registered format reads back what its writer wrote", "[io][formats]") {
  const std::filesystem::path dir = test::fresh_temp_dir("mesh_formats");
  const ObjDocument written = small_tetrahedron();
  for (const MeshFormat* format : mesh_formats()) {
    CAPTURE(format->name);
    REQUIRE(format->read != nullptr);
    REQUIRE(format->write != nullptr);
    const std::string path = (dir / ("mesh" + format->written_extension())).string();
    const std::vector<std::string> warnings =
        format->write(path, {GlbMesh{"", &written, nullptr, written.positions, nullptr}}, {});
    CHECK(warnings.empty());
    CHECK(&mesh_format_for_path(path) == format);
    const MeshFileContents read = format->read(path, {});
    CHECK(read.document.positions == written.positions);
    REQUIRE(read.document.faces.size() == written.faces.size());
    for (std::size_t f = 0; f < written.faces.size(); ++f)
      for (int c = 0; c < 3; ++c)
        CHECK(read.document.faces[f][c].position == written.faces[f][c].position);
  }
}

TEST_CASE("formats are found by name and by any of their extensions, in any case",
          "[io][formats]") {
  std::set<std::string> names;
  for (const MeshFormat* format : mesh_formats()) {
    CAPTURE(format->name);
    CHECK(names.insert(format->name).second);
    CHECK(&mesh_format_named(format->name) == format);
    REQUIRE_FALSE(format->extensions.empty());
    for (std::string extension : format->extensions) {
      CHECK(&mesh_format_for_path("dir/a" + extension) == format);
      for (char& c : extension) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
      CHECK(&mesh_format_for_path("dir/A" + extension) == format);
    }
  }
  CHECK(mesh_format_names().size() == mesh_formats().size());
  CHECK_THROWS_AS(mesh_format_named("stl"), std::invalid_argument);
  // No registered extension: read as the first format, whose reader names the problem.
  CHECK(&mesh_format_for_path("garment.txt") == mesh_formats().front());
}

TEST_CASE("a format holding one mesh per file refuses several", "[io][formats]") {
  const std::filesystem::path dir = test::fresh_temp_dir("mesh_formats_one");
  const ObjDocument written = small_tetrahedron();
  const GlbMesh mesh{"", &written, nullptr, written.positions, nullptr};
  for (const MeshFormat* format : mesh_formats()) {
    if (format->several_meshes) continue;
    CAPTURE(format->name);
    CHECK_THROWS_AS(
        format->write((dir / ("two" + format->written_extension())).string(), {mesh, mesh}, {}),
        OutputError);
  }
}

}  // namespace gr
