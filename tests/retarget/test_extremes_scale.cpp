#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <fmt/format.h>
#include <catch2/catch.hpp>

#include "core/io/obj_document.hpp"
#include "extremes_support.hpp"
#include "retarget/scene/normalization.hpp"

namespace fs = std::filesystem;
using namespace gr;

namespace {

/// Copies an OBJ (mesh or skeleton) with every `v` position mapped to scale · p + shift
/// and every other line kept; a mesh's material files are copied along.
std::string write_transformed(const std::string& source, const fs::path& dir,
                              const std::string& name, double scale, const Vector3d& shift) {
  std::ifstream in(source);
  const std::string path = (dir / name).string();
  std::ofstream out(path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("v ", 0) != 0) {
      out << line << '\n';
      continue;
    }
    std::istringstream fields(line.substr(2));
    Vector3d p;
    fields >> p.x() >> p.y() >> p.z();
    p = scale * p + shift;
    out << fmt::format("v {:.17g} {:.17g} {:.17g}\n", p.x(), p.y(), p.z());
  }
  out.close();
  copy_material_files(read_obj(source), dir.string());
  return path;
}

/// A scene's files; empty skeleton paths mean a scene without skeletons.
struct ScaleScene {
  std::string name;
  ScenePaths paths;
  bool skirt = false;
};

ScaleScene bundled_scene() {
  const std::string dir = "scenes/dress_form/";
  ScaleScene scene{"dress_form", {}, false};
  scene.paths.garment = test::project_file(dir + "garment.obj");
  scene.paths.avatar = test::project_file(dir + "avatar.obj");
  scene.paths.no_fit = test::project_file(dir + "no-fit.txt");
  return scene;
}

ScaleScene shared_skirt_scene() {
  ScaleScene scene{"foxgirl_skirt", {}, true};
  scene.paths.garment = test::shared_data("garments/skirt/garment.obj");
  scene.paths.avatar = test::shared_data("avatars/foxgirl/avatar.obj");
  scene.paths.source_skeleton = test::shared_data("garments/skirt/skeleton.obj");
  scene.paths.target_skeleton = test::shared_data("avatars/foxgirl/skeleton.obj");
  scene.paths.no_fit = test::shared_data("garments/skirt/no-fit.txt");
  return scene;
}

/// The garment after inflation and after the fit, retargeted from copies of the scene's
/// files transformed by x ↦ scale · x + shift and mapped back to the original frame
/// (#P×3 in input order), with the shrink depth.
struct ScaledRun {
  MatrixX3d inflated, fitted;
  double shrink_depth;
};

ScaledRun retarget_transformed(const ScaleScene& scene, double scale, const Vector3d& shift,
                               const std::string& name) {
  const std::string tag = scene.name + "_" + name;
  const fs::path in = test::fresh_temp_dir("extremes_scale_in_" + tag);
  const fs::path out = test::fresh_temp_dir("extremes_scale_out_" + tag);
  const auto transformed = [&](const std::string& source, const std::string& file) {
    return source.empty() ? source : write_transformed(source, in, file, scale, shift);
  };
  RetargetOptions options = test::quiet_options(transformed(scene.paths.garment, "garment.obj"),
                                                transformed(scene.paths.avatar, "avatar.obj"), out);
  options.inputs.source_skeleton = transformed(scene.paths.source_skeleton, "source_skeleton.obj");
  options.inputs.target_skeleton = transformed(scene.paths.target_skeleton, "target_skeleton.obj");
  options.inputs.no_fit = scene.paths.no_fit;
  options.skirt = scene.skirt;
  options.frames = true;
  const RetargetResult result = run_retarget(options);
  INFO(tag << ": " << result.message);
  REQUIRE(result.status == Outcome::kCertified);
  test::check_outputs_finite(out);
  // With skeletons, every boundary loop ends at its place along its bone.
  CHECK(result.report.fit.loop_offsets.empty() == options.inputs.source_skeleton.empty());
  for (const double offset : result.report.fit.loop_offsets) CHECK(offset < 1e-3);
  const auto back = [&](const std::string& path) -> MatrixX3d {
    return (read_obj(path).positions.rowwise() - shift.transpose()) / scale;
  };
  const std::string last_round =
      fmt::format("round_{:02d}_garment.obj", result.report.inflate.al_rounds);
  return {back((out / "frames" / last_round).string()), back(result.garment_path),
          result.report.shrink.depth};
}

}  // namespace

TEST_CASE(
    "extremes: a scene scaled by 1e-3 and 1e3 and moved by 1e4 gives the same "
    "certified garment",
    "[pipeline][extremes][scale][heavy]") {
  const ScaleScene scene = GENERATE(bundled_scene(), shared_skirt_scene());
  const ObjDocument avatar = read_obj(scene.paths.avatar);
  const double scene_size =
      (avatar.positions.colwise().maxCoeff() - avatar.positions.colwise().minCoeff()).maxCoeff();
  const ScaledRun reference = retarget_transformed(scene, 1.0, Vector3d::Zero(), "reference");

  struct Case {
    const char* name;
    double scale;
    Vector3d shift;
  };
  for (const Case& c :
       {Case{"scale_1e-3", 1e-3, Vector3d::Zero()}, Case{"scale_1e3", 1e3, Vector3d::Zero()},
        Case{"shift_1e4", 1.0, Vector3d(1e4, -1e4, 1e4)}}) {
    const ScaledRun outcome = retarget_transformed(scene, c.scale, c.shift, c.name);
    REQUIRE(outcome.fitted.rows() == reference.fitted.rows());
    const auto agreement = [&](const MatrixX3d& a, const MatrixX3d& b) {
      return (a - b).rowwise().norm().maxCoeff() / scene_size;
    };
    const double inflated = agreement(outcome.inflated, reference.inflated);
    const double fitted = agreement(outcome.fitted, reference.fitted);
    CAPTURE(scene.name, c.name, inflated, fitted);
    CHECK(outcome.shrink_depth == Approx(reference.shrink_depth).epsilon(1e-6));
    CHECK(inflated <= 1e-6);
    CHECK(fitted <= 1e-6);
  }
}

TEST_CASE(
    "normalization: rescaled and moved copies of a scene give bit-identical solver input, "
    "within half a lattice step of the exact map",
    "[pipeline][extremes][scale]") {
  const ScaleScene scene = bundled_scene();
  const Scene original = load_scene(scene.paths);
  const double lattice = lattice_spacing(RetargetParameters{}.dhat);
  const NormalizedScene reference = make_normalized_scene(original, lattice);
  const MatrixX3d exact =
      reference.normalization.garment_to_scene.apply_rows(original.garment.mesh.vertices);
  CHECK(lattice == std::ldexp(1.0, -20));
  CHECK((reference.garment.vertices - exact).cwiseAbs().maxCoeff() <= 0.5 * lattice);
  const MatrixX3d steps = reference.garment.vertices / lattice;
  CHECK((steps - steps.array().round().matrix()).cwiseAbs().maxCoeff() == 0.0);

  for (const auto& [scale, shift] :
       {std::pair{1e-3, Vector3d(0.0, 0.0, 0.0)}, std::pair{1e3, Vector3d(0.0, 0.0, 0.0)},
        std::pair{1.0, Vector3d(1e4, -1e4, 1e4)}}) {
    const fs::path dir = test::fresh_temp_dir(fmt::format("normalization_lattice_{}", scale));
    ScenePaths paths = scene.paths;
    paths.garment = write_transformed(scene.paths.garment, dir, "garment.obj", scale, shift);
    paths.avatar = write_transformed(scene.paths.avatar, dir, "avatar.obj", scale, shift);
    const NormalizedScene moved = make_normalized_scene(load_scene(paths), lattice);
    CAPTURE(scale, shift.transpose());
    CHECK(moved.garment.vertices == reference.garment.vertices);
    CHECK(moved.avatar.vertices == reference.avatar.vertices);
  }
}
