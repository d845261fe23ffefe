#include <filesystem>
#include <string>

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include "core/io/obj_document.hpp"
#include "extremes_support.hpp"

namespace fs = std::filesystem;
using namespace gr;

namespace {

const std::string kScene = "tools/scenes/dress_form/";

/// Copies an OBJ with every position mapped to scale · p + shift (materials copied too).
std::string write_transformed(const std::string& source, const fs::path& dir, double scale,
                              const Vector3d& shift) {
  const ObjDocument document = read_obj(source);
  const MatrixX3d positions = (scale * document.positions).rowwise() + shift.transpose();
  const std::string path = (dir / fs::path(source).filename()).string();
  write_obj(path, document, positions);
  copy_material_files(document, dir.string());
  return path;
}

/// The bundled scene's garment after inflation and after the fit, retargeted from copies
/// of its files transformed by x ↦ scale · x + shift, mapped back to the original frame
/// (#P×3 in input order), with the shrink depth.
struct Outcome {
  MatrixX3d inflated, fitted;
  double shrink_depth;
};

Outcome retarget_transformed(double scale, const Vector3d& shift, const std::string& name) {
  const fs::path in = test::fresh_temp_dir("extremes_scale_in_" + name);
  const fs::path out = test::fresh_temp_dir("extremes_scale_out_" + name);
  const std::string garment =
      write_transformed(test::project_file(kScene + "garment.obj"), in, scale, shift);
  const std::string avatar =
      write_transformed(test::project_file(kScene + "avatar.obj"), in, scale, shift);
  RetargetOptions options = test::quiet_options(garment, avatar, out);
  options.inputs.no_fit = test::project_file(kScene + "no-fit.txt");
  options.frames = true;
  const RetargetResult result = run_retarget(options);
  INFO(name << ": " << result.message);
  REQUIRE(result.status == RetargetStatus::kCertified);
  test::check_outputs_finite(out);
  const auto back = [&](const std::string& path) -> MatrixX3d {
    return (read_obj(path).positions.rowwise() - shift.transpose()) / scale;
  };
  const std::string last_round =
      fmt::format("round_{:02d}_garment.obj", result.report.al_rounds);
  return {back((out / "frames" / last_round).string()), back(result.garment_path),
          result.report.shrink_depth};
}

}  // namespace

TEST_CASE("extremes: the bundled scene scaled by 1e-3 and 1e3 and moved by 1e4 gives the "
          "same certified garment",
          "[pipeline][extremes][scale][heavy]") {
  const ObjDocument avatar = read_obj(test::project_file(kScene + "avatar.obj"));
  const double scene_size =
      (avatar.positions.colwise().maxCoeff() - avatar.positions.colwise().minCoeff()).maxCoeff();
  static const Outcome reference = retarget_transformed(1.0, Vector3d::Zero(), "reference");

  struct Case {
    const char* name;
    double scale;
    Vector3d shift;
  };
  const Case c = GENERATE(Case{"scale_1e-3", 1e-3, Vector3d::Zero()},
                          Case{"scale_1e3", 1e3, Vector3d::Zero()},
                          Case{"shift_1e4", 1.0, Vector3d(1e4, -1e4, 1e4)});
  const Outcome outcome = retarget_transformed(c.scale, c.shift, c.name);
  REQUIRE(outcome.fitted.rows() == reference.fitted.rows());
  const auto agreement = [&](const MatrixX3d& a, const MatrixX3d& b) {
    return (a - b).rowwise().norm().maxCoeff() / scene_size;
  };
  const double inflated = agreement(outcome.inflated, reference.inflated);
  const double fitted = agreement(outcome.fitted, reference.fitted);
  CAPTURE(c.name, inflated, fitted);
  // Shrink and inflation are exact checks and a well-posed solve: they agree to rounding.
  CHECK(outcome.shrink_depth == Approx(reference.shrink_depth).epsilon(1e-6));
  CHECK(inflated <= 1e-6);
  // The fit does not: its signed distance is an OpenVDB float grid built from float
  // vertex coordinates, which round differently once the scene is rescaled (phi moves by
  // about 1e-7), and the fit objective on this scene has nearly free modes (a tube skirt
  // sliding round and along a dress form of revolution), so the solver stops at a
  // different point of a flat valley. Measured: 5.8e-3 (1e3), 5.8e-3 (1e-3), 4.8e-3 (shift).
  CHECK(fitted <= 1e-2);
}
