#include <cstdlib>
#include <fstream>
#include <string>

#include <sys/wait.h>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "core/io/obj_document.hpp"
#include "core/mesh/simulation_mesh.hpp"
#include "test_support.hpp"
#include "validate/checks/mesh_intersections.hpp"

namespace {

int run_cli(const std::string& arguments) {
  const int status = std::system(
      (std::string(GR_CLI_PATH) + " " + arguments + " --quiet > /dev/null 2>&1").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/// The bundled scene's command-line inputs.
std::string dress_form_inputs() {
  return " --garment " + gr::test::project_file("scenes/dress_form/garment.obj") + " --avatar " +
         gr::test::project_file("scenes/dress_form/avatar.obj");
}

nlohmann::json read_json(const std::filesystem::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

}  // namespace

TEST_CASE("shrink command writes a certified shrunk avatar over the garment", "[cli][shrink]") {
  const auto out = gr::test::fresh_temp_dir("shrink_dress_form");
  const std::string garment = gr::test::project_file("scenes/dress_form/garment.obj");
  const std::string avatar = gr::test::project_file("scenes/dress_form/avatar.obj");
  REQUIRE(run_cli("shrink" + dress_form_inputs() + " --voxel-size 0.02 --out " + out.string()) ==
          0);
  const nlohmann::json report = read_json(out / "report.json");
  REQUIRE(report["found"] == true);
  REQUIRE(report["mode"] == "levelset");
  REQUIRE(report["depth"].get<double>() > 0.0);
  REQUIRE(report.contains("medial_vertices"));
  REQUIRE(report.contains("seconds"));

  // The written avatar has the avatar's faces and, read back in the garment's frame, is
  // free of the garment as written.
  const gr::ObjDocument written = gr::read_obj((out / "shrunk_avatar.obj").string());
  const gr::ObjDocument original = gr::read_obj(avatar);
  REQUIRE(written.faces.size() == original.faces.size());
  const gr::SimulationMesh shrunk = gr::make_simulation_mesh(written);
  const gr::SimulationMesh cloth = gr::make_simulation_mesh(gr::read_obj(garment));
  REQUIRE(gr::find_intersecting_face_pairs(shrunk.mesh, cloth.mesh).count == 0);
  // ... and the original avatar is not (the scene needs the shrink).
  REQUIRE(
      gr::find_intersecting_face_pairs(gr::make_simulation_mesh(original).mesh, cloth.mesh).count >
      0);
}

TEST_CASE("shrink command exits 3 and names the conflict when no shrink exists", "[cli][shrink]") {
  const auto dir = gr::test::fresh_temp_dir("shrink_no_valid");
  const auto out = dir / "out";
  // A sheet through the middle of the dress form: no erosion frees it.
  const std::string sheet = (dir / "sheet.obj").string();
  {
    std::ofstream obj(sheet);
    obj << "v -1 0.8 -1\nv 2 0.8 -1\nv 2 0.8 1\nv -1 0.8 1\nf 1 2 3\nf 1 3 4\n";
  }
  const std::string avatar = gr::test::project_file("scenes/dress_form/avatar.obj");
  REQUIRE(run_cli("shrink --garment " + sheet + " --avatar " + avatar +
                  " --voxel-size 0.02 --out " + out.string()) == 3);
  const nlohmann::json report = read_json(out / "report.json");
  REQUIRE(report["found"] == false);
  REQUIRE(report["conflict"]["garment_face"].get<int>() >= 0);
  REQUIRE(report["conflict"]["position"].size() == 3);
  // In the garment's frame: on the sheet's plane y = 0.8.
  REQUIRE(report["conflict"]["position"][1].get<double>() == Approx(0.8).margin(1e-6));
  REQUIRE_FALSE(std::filesystem::exists(out / "shrunk_avatar.obj"));
  // The most shrunk avatar tried is written for the user to see why, with what crosses.
  CHECK(std::filesystem::is_regular_file(out / "closest_shrunk_avatar.obj"));
  CHECK_FALSE(report["closest"]["crossing_garment_faces"].empty());
}

TEST_CASE("shrink command rejects skeleton mode without skeletons", "[cli][shrink]") {
  const auto out = gr::test::fresh_temp_dir("shrink_no_skeleton");
  REQUIRE(run_cli("shrink --mode skeleton" + dress_form_inputs() + " --out " + out.string()) == 2);
}
