#include <algorithm>
#include <cstdlib>
#include <fstream>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "core/io/gltf_document.hpp"
#include "core/io/gltf_fixture.hpp"
#include "core/io/mesh_file.hpp"
#include "extremes_support.hpp"
#include "gltf_scene.hpp"
#include "scenes/synthetic/skeleton_free_scenes.hpp"
#include "test_support.hpp"
#include "validate/certify/validation.hpp"
#include "validate/checks/mesh_intersections.hpp"
#include "validate/checks/self_intersections.hpp"
#include "validate/measure/surface_distance.hpp"

namespace gr {
namespace {

using test::run_gltf_validator;
using test::ValidatorRun;

/// Every joint of `skin` below `joint`, itself included.
std::vector<bool> subtree(const SkinBinding& skin, int joint) {
  std::vector<bool> in(skin.joints.size(), false);
  for (std::size_t j = 0; j < skin.joints.size(); ++j)
    for (int a = static_cast<int>(j); a >= 0; a = skin.joints[static_cast<std::size_t>(a)].parent)
      if (a == joint) in[j] = true;
  return in;
}

int joint_named(const SkinBinding& skin, const std::string& name) {
  for (std::size_t j = 0; j < skin.joints.size(); ++j)
    if (skin.joints[j].name == name) return static_cast<int>(j);
  FAIL("no joint " << name);
  return -1;
}

/// Linear blend skinning of rest positions (#P×3, world) when `joint` and everything below
/// it turn by `rotation` about the joint: v' = v + sum over the turned joints of w (P v - v).
MatrixX3d pose(const MatrixX3d& rest, const SkinBinding& skin, int joint,
               const Eigen::Matrix3d& rotation) {
  const std::vector<bool> moved = subtree(skin, joint);
  const Vector3d centre = skin.joints[static_cast<std::size_t>(joint)].world.topRightCorner<3, 1>();
  MatrixX3d posed = rest;
  for (Eigen::Index v = 0; v < rest.rows(); ++v) {
    const Vector3d p = rest.row(v).transpose();
    const Vector3d turned = centre + rotation * (p - centre);
    double share = 0.0;
    for (std::size_t j = 0; j < moved.size(); ++j)
      if (moved[j]) share += skin.weights(static_cast<Eigen::Index>(j), v);
    posed.row(v) = (p + share * (turned - p)).transpose();
  }
  return posed;
}

TriangleMesh with_positions(const ObjDocument& document, const MatrixX3d& positions) {
  TriangleMesh mesh = mesh_as_written(document);
  mesh.vertices = positions;
  return mesh;
}

double mean_abs_change(const std::vector<double>& a, const std::vector<double>& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) sum += std::abs(a[i] - b[i]);
  return sum / static_cast<double>(a.size());
}

TEST_CASE(
    "goblin_puffer from two GLB files: certified, skinned to the goblin, valid glTF, "
    "and posed with the body",
    "[gltf][pipeline]") {
  const auto dir = test::fresh_temp_dir("gltf_goblin_puffer");
  const std::string garment = (dir / "puffer.glb").string();
  const std::string avatar = (dir / "goblin.glb").string();
  const std::string no_fit = (dir / "no-fit.txt").string();
  test::write_skinned_garment_glb(test::shared_data("garments/puffer/garment.obj"),
                                  test::shared_data("garments/puffer/skeleton.obj"), garment);
  test::write_skinned_avatar_glb(test::shared_data("avatars/goblin/avatar.obj"),
                                 test::shared_data("avatars/goblin/skeleton.obj"),
                                 test::shared_data("avatars/goblin/skin.txt"), avatar);
  test::write_glb_no_fit(test::shared_data("garments/puffer/garment.obj"),
                         test::shared_data("garments/puffer/no-fit.txt"), garment, no_fit);
  const auto out = dir / "out";
  const test::CliRun run =
      test::run_cli({"retarget", "--garment", garment, "--avatar", avatar, "--no-fit", no_fit,
                     "--out", out.string(), "--quality", "fast", "--quiet"},
                    "gltf_goblin_puffer");
  INFO(run.out << run.err);
  REQUIRE(run.exit_code == 0);
  const std::string written = (out / "garment.glb").string();
  REQUIRE(std::filesystem::exists(written));
  REQUIRE_FALSE(std::filesystem::exists(out / "garment.obj"));

  const ValidatorRun validator = run_gltf_validator(written);
  INFO(validator.summary.dump());
  REQUIRE(validator.exit_code == 0);
  REQUIRE(validator.summary["errors"] == 0);

  // `validate` reads the GLB garment and avatar as `retarget` certified them.
  const test::CliRun check =
      test::run_cli({"validate", "--garment", written, "--avatar", avatar}, "gltf_validate");
  INFO(check.out << check.err);
  REQUIRE(check.exit_code == 0);

  const nlohmann::json report = nlohmann::json::parse(test::read_text(out / "report.json"));
  const nlohmann::json certificate =
      nlohmann::json::parse(test::read_text(out / "certificate.json"));
  REQUIRE(report["certified"] == true);
  const nlohmann::json& skin_report = report["skin"];
  REQUIRE(skin_report["written"] == true);
  const int matched = skin_report["matched_vertices"];
  const int inpainted = skin_report["inpainted_vertices"];
  REQUIRE(matched + inpainted == report["modelled"]["garment_vertices"].get<int>());
  REQUIRE(matched > inpainted);

  const GltfAsset result = read_gltf(written);
  const GltfAsset body = read_gltf(avatar);
  REQUIRE(result.gltf.skin.has_value());
  const SkinBinding& skin = *result.gltf.skin;
  REQUIRE(skin.joints.size() == body.gltf.skin->joints.size());
  for (Eigen::Index v = 0; v < skin.weights.cols(); ++v) {
    CAPTURE(v);
    REQUIRE(skin.weights.col(v).minCoeff() >= 0.0);
    REQUIRE((skin.weights.col(v).array() > 0.0).count() <= 4);
    REQUIRE(skin.weights.col(v).sum() == Approx(1.0).margin(1e-6));
  }
  // Materials, UVs and faces as in the input garment.
  const GltfAsset input = read_gltf(garment);
  REQUIRE(result.document.texcoords == input.document.texcoords);
  REQUIRE(result.document.faces.size() == input.document.faces.size());

  // Pose the goblin's left arm by its skin and the garment by the written one.
  const SkinBinding& body_skin = *body.gltf.skin;
  const int shoulder = joint_named(body_skin, "joint_3");
  const int elbow = joint_named(body_skin, "joint_4");
  const Vector3d upper_arm =
      body_skin.joints[static_cast<std::size_t>(elbow)].world.topRightCorner<3, 1>() -
      body_skin.joints[static_cast<std::size_t>(shoulder)].world.topRightCorner<3, 1>();
  struct Pose {
    const char* name;
    int joint;
    Eigen::Matrix3d rotation;
  };
  // The goblin stands Z up, facing -Y, arms hanging: the elbow bends about the axis across
  // the arm, the arm rises sideways about the Y axis (towards +Z for the +X arm).
  const Vector3d across = upper_arm.cross(Vector3d::UnitY()).normalized();
  const std::vector<Pose> poses = {
      {"bent elbow (60 degrees)", elbow, Eigen::AngleAxisd(M_PI / 3.0, across).toRotationMatrix()},
      {"raised arm (60 degrees)", shoulder,
       Eigen::AngleAxisd(-M_PI / 3.0, Vector3d::UnitY()).toRotationMatrix()}};
  const TriangleMesh rest_body = with_positions(body.document, body.document.positions);
  const TriangleMesh rest_garment = with_positions(result.document, result.document.positions);
  REQUIRE(find_intersecting_face_pairs(rest_garment, rest_body, 0).count == 0);
  const std::size_t rest_self = find_self_intersecting_face_pairs(rest_garment, 0).pairs.count;
  const std::vector<double> rest_gap = distances_to_surface(rest_body, rest_garment.vertices);

  for (const Pose& p : poses) {
    CAPTURE(p.name);
    const TriangleMesh posed_body = with_positions(
        body.document, pose(body.document.positions, body_skin, p.joint, p.rotation));
    const TriangleMesh posed_garment =
        with_positions(result.document, pose(result.document.positions, skin, p.joint, p.rotation));
    // The pose moves the arm: a garment left in place falls away from it (or into it).
    REQUIRE((posed_body.vertices - rest_body.vertices).rowwise().norm().maxCoeff() >
            0.2 * upper_arm.norm());
    const double skinned =
        mean_abs_change(distances_to_surface(posed_body, posed_garment.vertices), rest_gap);
    const double unskinned =
        mean_abs_change(distances_to_surface(posed_body, rest_garment.vertices), rest_gap);
    const std::size_t crossings = find_intersecting_face_pairs(posed_garment, posed_body, 0).count;
    const std::size_t self = find_self_intersecting_face_pairs(posed_garment, 0).pairs.count;
    WARN(p.name << ": mean change of the garment's distance to the body " << skinned
                << " skinned against " << unskinned << " left in place (avatar units); "
                << crossings << " garment-avatar face pairs intersect (0 at rest), " << self
                << " garment self pairs (" << rest_self << " at rest)");
    REQUIRE(skinned < 0.25 * unskinned);
  }
  WARN("skin transfer: " << skin_report["seconds"].get<double>() << " s; " << matched
                         << " vertices matched directly, " << inpainted << " inpainted ("
                         << 100.0 * inpainted / (matched + inpainted) << "%); certificate "
                         << (certificate["certified"] == true ? "certified" : "NOT certified"));
}

TEST_CASE("A textured GLB with tangents, written back, passes the validator", "[gltf]") {
  const auto dir = test::fresh_temp_dir("gltf_textured_validator");
  const ObjDocument skirt = read_obj(test::shared_data("garments/skirt/garment.obj"));
  const std::string input = (dir / "skirt.glb").string();
  test::write_textured_glb(skirt,
                           test::shared_data("garments/skirt/TXT_Aline Princess_Lower_AO.png"),
                           input, nullptr, true);
  const GltfAsset read = read_gltf(input);
  REQUIRE(read.gltf.has_tangents);
  // Moved, so normals and tangents are recomputed for new positions.
  MatrixX3d moved = read.document.positions;
  moved.col(0) *= 1.3;
  const std::string written = (dir / "written.glb").string();
  write_glb(written, read.document, &read.gltf, moved, nullptr);
  const ValidatorRun validator = run_gltf_validator(written);
  INFO(validator.summary.dump());
  REQUIRE(validator.exit_code == 0);
  REQUIRE(validator.summary["errors"] == 0);
  // The skirt's PNG uses features the validator flags (IMAGE_FEATURES_UNSUPPORTED): the
  // image is carried as it is; nothing written here may draw a warning.
  for (const auto& code : validator.summary["warning_codes"])
    REQUIRE(code.get<std::string>().rfind("IMAGE_", 0) == 0);
}

TEST_CASE("The validator runner fails on a GLB with errors", "[gltf]") {
  const auto dir = test::fresh_temp_dir("gltf_validator_broken");
  ObjDocument triangle;
  triangle.positions.resize(3, 3);
  triangle.positions << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  triangle.faces = {{ObjCorner{0, -1, -1}, ObjCorner{1, -1, -1}, ObjCorner{2, -1, -1}}};
  const std::string path = (dir / "triangle.glb").string();
  write_glb(path, triangle, nullptr, triangle.positions, nullptr);
  REQUIRE(run_gltf_validator(path).exit_code == 0);
  // A POSITION bound that lies: the validator reports it as an error.
  std::string bytes = test::read_text(path);
  const auto at = bytes.find("\"max\":[");
  REQUIRE(at != std::string::npos);
  bytes[at + 7] = bytes[at + 7] == '1' ? '5' : '7';
  std::ofstream(path, std::ios::binary) << bytes;
  const ValidatorRun broken = run_gltf_validator(path);
  INFO(broken.summary.dump());
  REQUIRE(broken.exit_code == 1);
  REQUIRE(broken.summary["errors"].get<int>() > 0);
}

}  // namespace

TEST_CASE("An OBJ garment written as GLB is certified, validated and gets its report page",
          "[gltf]") {
  // Every face corner has a UV of its own, so the GLB splits every vertex: the report page
  // maps the written vertices back to the OBJ's through the faces.
  const auto dir = test::fresh_temp_dir("gltf_obj_to_glb");
  const SkeletonFreeScene scene = make_skeleton_free_scene(SkeletonFreeFamily::kPatchSphere,
                                                           {6, 0.0, 0.0, 1.0, Vector3d::Zero()});
  {
    std::ofstream obj(dir / "garment.obj");
    obj.precision(17);
    for (Eigen::Index v = 0; v < scene.garment.vertices.rows(); ++v)
      obj << "v " << scene.garment.vertices.row(v) << '\n';
    for (Eigen::Index c = 0; c < 3 * scene.garment.faces.rows(); ++c)
      obj << "vt " << (c % 7) / 7.0 << ' ' << (c % 5) / 5.0 << '\n';
    for (Eigen::Index f = 0; f < scene.garment.faces.rows(); ++f) {
      obj << 'f';
      for (int k = 0; k < 3; ++k)
        obj << ' ' << scene.garment.faces(f, k) + 1 << '/' << 3 * f + k + 1;
      obj << '\n';
    }
  }
  write_obj((dir / "avatar.obj").string(), scene.avatar);
  const test::CliRun run =
      test::run_cli({"retarget", "--garment", (dir / "garment.obj").string(), "--avatar",
                     (dir / "avatar.obj").string(), "--out", (dir / "run").string(), "--quality",
                     "fast", "--format", "glb", "--quiet"},
                    "gltf_obj_to_glb");
  CAPTURE(run.out, run.err);
  REQUIRE(run.exit_code == 0);
  CHECK(std::filesystem::exists(dir / "run" / "report.html"));
  CHECK_FALSE(std::filesystem::exists(dir / "run" / "garment.obj"));
  const GltfAsset written = read_gltf((dir / "run" / "garment.glb").string());
  CHECK(written.document.positions.rows() == 3 * scene.garment.faces.rows());
  const ValidatorRun validator = run_gltf_validator((dir / "run" / "garment.glb").string());
  INFO(validator.summary.dump());
  CHECK(validator.exit_code == 0);
  CHECK(validator.summary["errors"] == 0);
}

}  // namespace gr

namespace gr {

TEST_CASE("Production outfits retarget onto an undressed body of another shape",
          "[gltf][shared][real]") {
  // Garments that cross themselves, come in pieces and close around the body (see
  // ../shared/data/real/README.md), each onto a whole body of the other sex.
  const auto [file, mesh] = GENERATE(
      std::make_pair(std::string("female-pose-standing.glb"), std::string("Wolf3D_Outfit_Top.002")),
      // Heeled shoes onto flat feet: turned flat by their skin, fitted holding their pattern.
      std::make_pair(std::string("female-pose-standing.glb"),
                     std::string("Wolf3D_Outfit_Footwear.002")),
      std::make_pair(std::string("male-outfit.glb"), std::string("Wolf3D_Outfit_Bottom")),
      std::make_pair(std::string("male-outfit.glb"), std::string("Wolf3D_Outfit_Top")));
  CAPTURE(file, mesh);
  const std::string garment = test::shared_data("real/" + file);
  const std::string avatar = test::shared_data("real/female-full-body.glb");
  const auto out = test::fresh_temp_dir("real_outfit") / "run";
  const test::CliRun run = test::run_cli({"retarget", "--garment", garment, "--garment-mesh", mesh,
                                          "--avatar", avatar, "--out", out.string(), "--quiet"},
                                         "real_outfit");
  CAPTURE(run.out, run.err);
  REQUIRE(run.exit_code == 0);
  const auto report = nlohmann::json::parse(test::read_text(out / "report.json"));
  CAPTURE(report["pose"].dump());
  CHECK(report["shape"]["mean_edge_change"].get<double>() <= 0.30);
  // The dress is turned into the body's pose by its skin, which folds it at the turn: the
  // crossings that makes are pushed apart. A garment that keeps its pose says why.
  if (mesh == "Wolf3D_Outfit_Top.002") {
    CHECK(report["pose"]["posed"] == true);
    CHECK(report["pose"]["untangled_pairs"].get<int>() > 0);
  } else if (report["pose"]["posed"] == false) {
    CHECK_FALSE(report["pose"]["reason"].get<std::string>().empty());
  }

  // The written file read back: free of the whole avatar (body, head and eyes merged), and
  // crossing itself only where the input did.
  const GltfAsset written = read_gltf((out / "garment.glb").string());
  const TriangleMesh worn = mesh_as_written(written.document);
  const TriangleMesh body = mesh_as_written(read_gltf_meshes(avatar, {}).document);
  CHECK(body.faces.rows() == 14918);
  CHECK(find_intersecting_face_pairs(worn, body).count == 0);
  const auto certificate = nlohmann::json::parse(test::read_text(out / "certificate.json"));
  CHECK(certificate["certified"] == true);
  CHECK(certificate["counts"]["garment_self_intersections"] == 0);
  const auto input_faces = read_gltf(garment, mesh).document.faces.size();
  const auto opened = report["pierced_faces"]["opened"].size();
  CHECK(written.document.faces.size() == input_faces - opened);
  CHECK(written.gltf.skin.has_value());

  const ValidatorRun validator = run_gltf_validator((out / "garment.glb").string());
  CHECK(validator.exit_code == 0);
  CHECK(validator.summary["errors"] == 0);
}

}  // namespace gr
