// The untangle through the pipeline: crossings the input came with pushed apart before the
// solve, within a garment and between the layers of an outfit; what it cannot undo kept.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "core/io/obj_document.hpp"
#include "core/mesh/simulation_mesh.hpp"
#include "extremes_support.hpp"
#include "garment/outfit_meshes.hpp"
#include "retarget/retarget.hpp"
#include "scenes/synthetic/tangled_garments.hpp"
#include "validate/checks/self_intersections.hpp"

namespace gr {
namespace {

/// Every vertex of a mesh of `count` vertices listed, so that the garment hangs free.
void write_all_no_fit(const std::filesystem::path& path, Eigen::Index count) {
  std::ofstream out(path);
  for (Eigen::Index v = 0; v < count; ++v) out << v << '\n';
}

/// The part of `t.garment` made of the faces of `layer`, its vertices renumbered.
TriangleMesh layer_of(const TangledGarment& t, int layer) {
  std::vector<int> id(static_cast<std::size_t>(t.garment.vertices.rows()), -1);
  std::vector<Eigen::RowVector3i> faces;
  std::vector<Eigen::RowVector3d> vertices;
  for (Eigen::Index f = 0; f < t.garment.faces.rows(); ++f) {
    if (t.face_layer[static_cast<std::size_t>(f)] != layer) continue;
    Eigen::RowVector3i face;
    for (int k = 0; k < 3; ++k) {
      int& v = id[static_cast<std::size_t>(t.garment.faces(f, k))];
      if (v < 0) {
        v = static_cast<int>(vertices.size());
        vertices.push_back(t.garment.vertices.row(t.garment.faces(f, k)));
      }
      face[k] = v;
    }
    faces.push_back(face);
  }
  TriangleMesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(vertices.size()), 3);
  for (std::size_t v = 0; v < vertices.size(); ++v)
    mesh.vertices.row(static_cast<Eigen::Index>(v)) = vertices[v];
  mesh.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    mesh.faces.row(static_cast<Eigen::Index>(f)) = faces[f];
  return mesh;
}

nlohmann::json read_json(const std::filesystem::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

}  // namespace

TEST_CASE("untangle end to end: a fold through a fold starts the solve untangled",
          "[untangle][end-to-end]") {
  // The two sheets 0.1 over the top of the unit sphere avatar, hanging free.
  TriangleMesh garment = make_fold_through_fold(0.004).garment;
  garment.vertices.col(2).array() += 1.1;
  REQUIRE(find_self_intersecting_face_pairs(garment).pairs.count > 0);
  RetargetOptions options = test::synthetic_scene("untangle_fold", garment);
  const std::filesystem::path dir = std::filesystem::path(options.inputs.garment).parent_path();
  write_all_no_fit(dir / "no-fit.txt", garment.vertices.rows());
  options.inputs.no_fit = (dir / "no-fit.txt").string();
  const RetargetResult result = test::run_and_check(options);
  INFO(result.message);
  CHECK(result.status == Outcome::kCertified);
  const nlohmann::json report = read_json(result.report_path);
  const nlohmann::json& untangle = report["untangle"];
  CHECK(untangle["pairs"].get<int>() > 0);
  CHECK(untangle["resolved"] == untangle["pairs"]);
  CHECK(untangle["resolved_share"].get<double>() == 1.0);
  CHECK(untangle["left_pairs"].empty());
  CHECK(untangle["max_displacement"].get<double>() > 0.0);
  CHECK(report["inherited_crossings"]["pairs"] == 0);
  const nlohmann::json certificate = read_json(dir / "out" / "certificate.json");
  CHECK(certificate["certified"] == true);
  CHECK(certificate["counts"]["garment_self_intersections"] == 0);
  CHECK(certificate["counts"]["inherited_self_intersections"] == 0);
  // The written garment crosses nothing, checked on the file.
  const TriangleMesh written = make_simulation_mesh(read_obj(result.garment_path)).mesh;
  CHECK(find_self_intersecting_face_pairs(written).pairs.count == 0);
}

TEST_CASE("untangle end to end: layers crossing at a hem are untangled against each other",
          "[untangle][end-to-end][outfit]") {
  const TangledGarment t = make_layers_crossing_at_hem(0.004);
  const std::filesystem::path dir = test::fresh_temp_dir("untangle_layers");
  const TriangleMesh inner = layer_of(t, 0), outer = layer_of(t, 1);
  write_obj((dir / "inner.obj").string(), inner);
  write_obj((dir / "outer.obj").string(), outer);
  write_all_no_fit(dir / "inner.no-fit.txt", inner.vertices.rows());
  write_all_no_fit(dir / "outer.no-fit.txt", outer.vertices.rows());
  write_obj((dir / "body.obj").string(),
            test::translated(test::capsule_body(0.25, 0.6), {0, 0, 0.35}));
  // Given outer first, and the order inside to outside named.
  RetargetOptions options =
      test::quiet_options((dir / "outer.obj").string(), (dir / "body.obj").string(), dir / "out");
  options.inputs.no_fit = (dir / "outer.no-fit.txt").string();
  options.inputs.more_garments.push_back(
      {(dir / "inner.obj").string(), "", (dir / "inner.no-fit.txt").string()});
  options.layer_order = {"inner", "outer"};
  options.overrides.set("voxel_size", test::kSyntheticVoxelSize);
  options.overrides.set("max_newton_iterations", test::kSyntheticNewtonCap);
  const RetargetResult result = test::run_and_check(options);
  INFO(result.message);
  CHECK(result.status == Outcome::kCertified);
  const nlohmann::json report = read_json(result.report_path);
  const nlohmann::json& untangle = report["untangle"];
  CHECK(untangle["layer_pairs"].get<int>() > 0);
  CHECK(untangle["layer_pairs_resolved"] == untangle["layer_pairs"]);
  CHECK(untangle["resolved"] == untangle["pairs"]);
  CHECK(report["inherited_crossings"]["pairs"] == 0);
  const nlohmann::json certificate = read_json(dir / "out" / "certificate.json");
  CHECK(certificate["certified"] == true);
  CHECK(certificate["counts"]["garment_garment_intersections"] == 0);
  CHECK(certificate["counts"]["inherited_layer_intersections"] == 0);
  // The outer garment went out, not in: its tucked hem further from the axis, and the
  // layer as a whole too.
  const MatrixX3d written_outer = read_obj((dir / "out" / "outer.obj").string()).positions;
  REQUIRE(written_outer.rows() == outer.vertices.rows());
  double widest = 0.0, outward = 0.0;
  for (Eigen::Index v = 0; v < outer.vertices.rows(); ++v) {
    const double moved =
        written_outer.row(v).head<2>().norm() - outer.vertices.row(v).head<2>().norm();
    widest = std::max(widest, moved);
    outward += moved;
  }
  CHECK(widest > 1e-3);
  CHECK(outward > 0.0);
}

TEST_CASE(
    "untangle end to end: a strap through a band wall stays, listed, and nothing new "
    "crosses",
    "[untangle][end-to-end][inherited]") {
  TriangleMesh garment = make_strap_through_band(0.0, true).garment;
  const std::filesystem::path dir = test::fresh_temp_dir("untangle_strap_wall");
  write_obj((dir / "garment.obj").string(), garment);
  write_all_no_fit(dir / "no-fit.txt", garment.vertices.rows());
  write_obj((dir / "body.obj").string(),
            test::translated(test::capsule_body(0.15, 0.3), {0, 0, 0.06}));
  RetargetOptions options =
      test::quiet_options((dir / "garment.obj").string(), (dir / "body.obj").string(), dir / "out");
  options.inputs.no_fit = (dir / "no-fit.txt").string();
  options.overrides.set("voxel_size", test::kSyntheticVoxelSize);
  options.overrides.set("max_newton_iterations", test::kSyntheticNewtonCap);
  const RetargetResult result = test::run_and_check(options);
  INFO(result.message);
  CHECK(result.status == Outcome::kCertified);
  const nlohmann::json report = read_json(result.report_path);
  const nlohmann::json& untangle = report["untangle"];
  // The strap still crosses the wall, on the faces it did or on others.
  CHECK(untangle["remaining"].get<int>() > 0);
  CHECK(untangle["remaining"] == untangle["left"].get<int>() + untangle["added"].get<int>());
  CHECK(untangle["left_pairs"].size() == untangle["remaining"].get<std::size_t>());
  for (const nlohmann::json& left : untangle["left_pairs"]) {
    CHECK(left["faces"].size() == 2);
    CHECK_FALSE(left["reason"].get<std::string>().empty());
  }
  CHECK(report["inherited_crossings"]["pairs"] == untangle["remaining"]);
  const nlohmann::json certificate = read_json(dir / "out" / "certificate.json");
  CHECK(certificate["certified"] == true);
  CHECK(certificate["counts"]["garment_self_intersections"] == 0);
}

}  // namespace gr
