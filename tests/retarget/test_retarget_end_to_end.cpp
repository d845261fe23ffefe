#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "core/io/obj_document.hpp"
#include "core/mesh/simulation_mesh.hpp"
#include "test_support.hpp"
#include "validate/measure/surface_distance.hpp"

namespace fs = std::filesystem;

namespace {

const std::string kScene = "scenes/dress_form/";

std::vector<std::string> bundled_args(const fs::path& out) {
  return {"retarget",
          "--garment",
          gr::test::project_file(kScene + "garment.obj"),
          "--avatar",
          gr::test::project_file(kScene + "avatar.obj"),
          "--no-fit",
          gr::test::project_file(kScene + "no-fit.txt"),
          "--out",
          out.string()};
}

/// One balanced run of the bundled scene, shared by the sections below.
const gr::test::CliRun& bundled_run(const fs::path& out) {
  static const gr::test::CliRun run = gr::test::run_cli(bundled_args(out), "e2e");
  return run;
}

nlohmann::json read_json(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

}  // namespace

TEST_CASE("retarget of the bundled scene is certified and faithful to the input asset",
          "[pipeline][e2e]") {
  static const fs::path out = gr::test::fresh_temp_dir("e2e_bundled");
  const gr::test::CliRun& run = bundled_run(out);
  CAPTURE(run.out, run.err);
  REQUIRE(run.exit_code == 0);
  CHECK_THAT(run.out, Catch::StartsWith("certified"));

  const gr::ObjDocument input = gr::read_obj(gr::test::project_file(kScene + "garment.obj"));
  const gr::ObjDocument output = gr::read_obj((out / "garment.obj").string());

  SECTION("same vertex order, UVs, faces, groups and materials; positions moved and finite") {
    REQUIRE(output.positions.rows() == input.positions.rows());
    CHECK(output.texcoords == input.texcoords);
    REQUIRE(output.faces.size() == input.faces.size());
    for (std::size_t f = 0; f < input.faces.size(); ++f)
      for (std::size_t k = 0; k < 3; ++k) {
        CHECK(output.faces[f][k].position == input.faces[f][k].position);
        CHECK(output.faces[f][k].texcoord == input.faces[f][k].texcoord);
      }
    REQUIRE(output.statements.size() == input.statements.size());
    for (std::size_t i = 0; i < input.statements.size(); ++i)
      CHECK(output.statements[i].text == input.statements[i].text);
    CHECK(output.material_libraries == input.material_libraries);
    CHECK(fs::exists(out / "garment.mtl"));
    CHECK(output.positions.allFinite());
    CHECK((output.positions - input.positions).rowwise().norm().maxCoeff() > 1e-3);
    // Welded seam duplicates move together: the seam stays closed.
    const gr::SimulationMesh sim = gr::make_simulation_mesh(input);
    for (Eigen::Index i = 0; i < input.positions.rows(); ++i) {
      const int s = sim.obj_to_sim[static_cast<std::size_t>(i)];
      if (s >= 0) CHECK(output.positions.row(i) == output.positions.row(sim.sim_to_obj[s]));
    }
  }

  SECTION("every vertex ends outside the avatar, the hem moves only as far as it must") {
    const gr::ObjDocument avatar_doc = gr::read_obj(gr::test::project_file(kScene + "avatar.obj"));
    const gr::SimulationMesh avatar = gr::make_simulation_mesh(avatar_doc);
    const std::vector<double> distance = gr::distances_to_surface(avatar.mesh, output.positions);
    // The dress form is a surface of revolution about a vertical axis through (0.35, ·, -0.2):
    // outside means farther from the axis than the surface, and never on it.
    for (Eigen::Index i = 0; i < output.positions.rows(); ++i) {
      CHECK(distance[static_cast<std::size_t>(i)] > 0.0);
      const gr::RowVector3d p = output.positions.row(i);
      const double axis_distance = std::hypot((p.x() - 0.35) / 1.1, (p.z() + 0.2) / 0.9);
      double nearest_radius = 0.0;
      double nearest_height = 1e9;
      for (Eigen::Index v = 0; v < avatar.mesh.vertices.rows(); ++v) {
        const gr::RowVector3d q = avatar.mesh.vertices.row(v);
        if (std::abs(q.y() - p.y()) < nearest_height) {
          nearest_height = std::abs(q.y() - p.y());
          nearest_radius = std::hypot((q.x() - 0.35) / 1.1, (q.z() + 0.2) / 0.9);
        }
      }
      CHECK(axis_distance > nearest_radius - 0.01);
    }
    // The no-fit hem rows are not pulled onto the body: they move with the cloth around
    // them, no further than the hips push the fitted rows (with some slack for the drape).
    std::ifstream no_fit(gr::test::project_file(kScene + "no-fit.txt"));
    std::vector<bool> hem(static_cast<std::size_t>(output.positions.rows()), false);
    for (int id; no_fit >> id;) hem[static_cast<std::size_t>(id)] = true;
    double hem_motion = 0.0, fitted_motion = 0.0;
    for (std::size_t i = 0; i < hem.size(); ++i) {
      const auto row = static_cast<Eigen::Index>(i);
      const double motion = (output.positions.row(row) - input.positions.row(row)).norm();
      (hem[i] ? hem_motion : fitted_motion) = std::max(hem[i] ? hem_motion : fitted_motion, motion);
    }
    CAPTURE(hem_motion, fitted_motion);
    CHECK(hem_motion <= 1.5 * fitted_motion);
  }

  SECTION("report and certificate are present and consistent") {
    const nlohmann::json report = read_json(out / "report.json");
    const nlohmann::json certificate = read_json(out / "certificate.json");
    CHECK(report["certified"] == true);
    CHECK(certificate["certified"] == true);
    CHECK(certificate["kind"] == "certificate");
    CHECK(certificate["counts"]["garment_avatar_intersections"] == 0);
    CHECK(certificate["counts"]["garment_self_intersections"] == 0);
    CHECK(report["min_distance"]["normalized"].get<double>() > 0.0);
    CHECK(report["min_distance"]["normalized"].get<double>() <
          report["parameters"]["dhat"].get<double>() * 5);
    CHECK(report["inflate"]["status"] == "snapped");
    CHECK(report["inflate"]["al_rounds"].get<int>() >= 1);
    CHECK(report["fit"]["newton_iterations"].get<int>() >= 1);
    const auto& seconds = report["seconds"];
    double stages = 0.0;
    for (const char* s : {"read", "normalize", "shrink", "inflate", "fit", "write", "certify"}) {
      CHECK(seconds[s].get<double>() >= 0.0);
      stages += seconds[s].get<double>();
    }
    CHECK(stages <= seconds["total"].get<double>() + 1e-6);
    CHECK(report["fit_error"]["mean"].get<double>() > 0.0);
    CHECK(report["fit_error"]["p95"].get<double>() >=
          report["fit_error"]["mean"].get<double>() * 0.5);
    CHECK(report["modelled"]["avatar_faces_modelled"].get<int>() <=
          report["modelled"]["avatar_faces_total"].get<int>());
    CHECK(report["modelled"]["fit_faces"].get<int>() <
          report["modelled"]["garment_faces"].get<int>());
    CHECK(report["modelled"]["self_contact_where"] == "where the garment can fold onto itself");
    for (const char* stage : {"inflate", "fit"}) {
      const double share = report["modelled"]["fold_free_face_fraction"][stage].get<double>();
      CHECK((share >= 0.0 && share <= 1.0));
    }
    CHECK(report["position"]["loop_offsets"].empty());  // no skeletons: no loops held
    for (const auto& [term, value] : report["energies"].items()) {
      CAPTURE(term);
      CHECK(std::isfinite(value.get<double>()));
    }
    // The certificate names the file it certified by its hash.
    CHECK(certificate["extra"]["output"]["sha256"].get<std::string>().size() == 64);
  }

  SECTION("the written garment passes validate on its own") {
    const gr::test::CliRun check =
        gr::test::run_cli({"validate", "--garment", (out / "garment.obj").string(), "--avatar",
                           gr::test::project_file(kScene + "avatar.obj")},
                          "e2e_validate");
    CAPTURE(check.out, check.err);
    CHECK(check.exit_code == 0);
  }
}

TEST_CASE("the same inputs and thread count give byte-identical output files", "[pipeline][e2e]") {
  const fs::path first = gr::test::fresh_temp_dir("e2e_det_a");
  const fs::path second = gr::test::fresh_temp_dir("e2e_det_b");
  for (const auto& out : {first, second}) {
    auto args = bundled_args(out);
    for (const char* extra : {"--quality", "fast", "--threads", "2", "--quiet"})
      args.push_back(extra);
    const gr::test::CliRun run = gr::test::run_cli(args, "e2e_det");
    CAPTURE(run.err);
    REQUIRE(run.exit_code == 0);
  }
  const auto bytes = [](const fs::path& p) { return gr::test::read_text(p); };
  CHECK(bytes(first / "garment.obj") == bytes(second / "garment.obj"));
  CHECK(bytes(first / "garment.mtl") == bytes(second / "garment.mtl"));
}
