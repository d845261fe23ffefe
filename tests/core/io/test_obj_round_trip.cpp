#include <filesystem>
#include <fstream>
#include <string>

#include <catch2/catch.hpp>

#include "core/io/obj_document.hpp"
#include "core/mesh/simulation_mesh.hpp"
#include "test_support.hpp"

namespace {

void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

}  // namespace

TEST_CASE("shared garments and avatars survive read, write, read", "[io][obj]") {
  const std::string file =
      GENERATE(as<std::string>{}, "garments/skirt/garment.obj", "garments/puffer/garment.obj",
               "avatars/foxgirl/avatar.obj", "avatars/goblin/avatar.obj");
  CAPTURE(file);
  const gr::ObjDocument first = gr::read_obj(gr::test::shared_data(file));
  const auto dir = gr::test::fresh_temp_dir("round_trip");
  const std::string written = (dir / "mesh.obj").string();
  gr::write_obj(written, first, first.positions);
  const gr::ObjDocument second = gr::read_obj(written);

  REQUIRE(second.positions.rows() == first.positions.rows());
  CHECK((second.positions.array() == first.positions.array()).all());
  REQUIRE(second.faces.size() == first.faces.size());
  REQUIRE(second.texcoords == first.texcoords);
  CHECK(second.statements.size() == first.statements.size());
  for (std::size_t i = 0; i < first.statements.size(); ++i) {
    CHECK(second.statements[i].text == first.statements[i].text);
    CHECK(second.statements[i].first_face == first.statements[i].first_face);
  }
  CHECK(second.material_libraries == first.material_libraries);
  bool corners_equal = true;
  std::size_t normals_with_input = 0;
  std::size_t normals_agreeing = 0;
  for (std::size_t f = 0; f < first.faces.size(); ++f)
    for (std::size_t k = 0; k < 3; ++k) {
      corners_equal &= first.faces[f][k].position == second.faces[f][k].position &&
                       first.faces[f][k].texcoord == second.faces[f][k].texcoord;
      // Recomputed normals point the way the input's did (same shading).
      if (first.faces[f][k].normal >= 0) {
        const Eigen::Vector3d a = first.normals.row(first.faces[f][k].normal);
        const Eigen::Vector3d b = second.normals.row(second.faces[f][k].normal);
        ++normals_with_input;
        normals_agreeing += a.normalized().dot(b) > 0.0;
      }
    }
  CHECK(corners_equal);
  // Recomputed normals follow the winding; a few input faces disagree with their own
  // stored normals (overlapping avatar parts), so most, not all, must agree.
  CAPTURE(normals_with_input, normals_agreeing);
  CHECK(normals_agreeing >= normals_with_input * 99 / 100);
}

TEST_CASE("OBJ faces in all four index forms and negative indices", "[io][obj]") {
  const auto dir = gr::test::fresh_temp_dir("obj_forms");
  write_text(dir / "forms.obj",
             "mtllib forms.mtl\n"
             "o part\n"
             "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
             "vt 0 0\nvt 1 0\nvt 1 1\nvn 0 0 1\n"
             "g top\nusemtl red\ns 1\n"
             "f 1 2 3\n"
             "f 1/1 2/2 3/3\n"
             "f 1//1 2//1 3//1\n"
             "f -4/-3/-1 -3/-2/-1 -2/-1/-1 -1/-1/-1\n");
  const gr::ObjDocument doc = gr::read_obj((dir / "forms.obj").string());
  REQUIRE(doc.positions.rows() == 4);
  REQUIRE(doc.faces.size() == 5);  // three triangles and one quad split in two
  CHECK(doc.faces[0][2].texcoord == -1);
  CHECK(doc.faces[1][2].texcoord == 2);
  CHECK(doc.faces[2][0].normal == 0);
  CHECK(doc.faces[2][0].texcoord == -1);
  CHECK(doc.faces[3][0].position == 0);
  CHECK(doc.faces[4][2].position == 3);
  CHECK(doc.faces[4][2].texcoord == 2);
  REQUIRE(doc.warnings.size() == 1);
  CHECK_THAT(doc.warnings[0], Catch::Contains("1 polygons"));
  REQUIRE(doc.statements.size() == 4);
  CHECK(doc.statements[0].text == "o part");
  CHECK(doc.statements[1].text == "g top");
  CHECK(doc.statements[3].first_face == 0);
  CHECK(doc.material_libraries == std::vector<std::string>{"forms.mtl"});

  gr::MatrixX3d moved = doc.positions;
  moved.col(2).array() += 0.1 / 3.0;
  gr::write_obj((dir / "moved.obj").string(), doc, moved);
  const gr::ObjDocument back = gr::read_obj((dir / "moved.obj").string());
  CHECK((back.positions.array() == moved.array()).all());
  // Faces that had normals still have them; the others still have none.
  CHECK(back.faces[0][0].normal == -1);
  CHECK(back.faces[2][0].normal >= 0);
  CHECK(back.normals.row(back.faces[2][0].normal).isApprox(Eigen::RowVector3d(0, 0, 1)));
}

TEST_CASE("welding merges bit-identical positions and keeps the maps", "[io][mesh]") {
  const auto dir = gr::test::fresh_temp_dir("weld");
  write_text(dir / "seam.obj",
             "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 5 5 5\n"
             "f 1 2 3\nf 4 6 5\nf 2 4 3\n");
  const gr::ObjDocument doc = gr::read_obj((dir / "seam.obj").string());
  const gr::SimulationMesh sim = gr::make_simulation_mesh(doc);
  CHECK(sim.mesh.vertices.rows() == 4);
  CHECK(sim.mesh.faces.rows() == 2);
  CHECK(sim.collapsed_faces == 1);
  CHECK(sim.obj_to_sim[3] == sim.obj_to_sim[1]);
  CHECK(sim.obj_to_sim[6] == -1);
  const gr::MatrixX3d out = gr::export_positions(
      doc, sim, sim.mesh.vertices, [](const gr::Vector3d& p) { return gr::Vector3d(p * 2.0); });
  CHECK(out.row(3) == doc.positions.row(3));
  CHECK(out.row(6) == gr::RowVector3d(10, 10, 10));
}

TEST_CASE("atomic writes leave no file when the folder is missing", "[io][atomic]") {
  const auto dir = gr::test::fresh_temp_dir("atomic");
  gr::ObjDocument doc = gr::read_obj(gr::test::project_file("scenes/dress_form/garment.obj"));
  const auto target = dir / "missing_folder" / "out.obj";
  CHECK_THROWS(gr::write_obj(target.string(), doc, doc.positions));
  CHECK_FALSE(std::filesystem::exists(target));
  CHECK(std::distance(std::filesystem::directory_iterator(dir), {}) == 0);
}
