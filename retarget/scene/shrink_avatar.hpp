#pragma once

#include <optional>

#include <nlohmann/json.hpp>
#include <string>

#include "core/common/interrupter.hpp"
#include "retarget/outcome.hpp"
#include "retarget/run/run_control.hpp"
#include "retarget/scene/scene.hpp"
#include "shrink/shrunk_avatar/shrink_result.hpp"

namespace gr {

class SignedDistanceGrid;
struct NormalizedScene;

/// How the avatar is shrunk: eroded along its signed distance, or collapsed onto the
/// source skeleton's bones.
enum class ShrinkMode { kLevelset, kSkeleton };

/// "levelset" or "skeleton".
const char* to_string(ShrinkMode mode);
/// The mode named `name`. @throw InputError for any other name.
ShrinkMode parse_shrink_mode(const std::string& name);

/// How far outside the avatar the pipeline's signed-distance grid holds distances, and
/// first also how deep inside (normalized units): the fit pulls garment points only from
/// within it, and most level-set shrinks need no deeper erosion.
constexpr double kDistanceBand = 0.1;

/// The avatar's signed distance as the pipeline builds it: a narrow band of kDistanceBand
/// inside the surface, and of `exterior_band` (at least kDistanceBand) outside, where the
/// fit reads it. `interrupter` sees its stages (build_signed_distance).
/// @throw Interrupted from `interrupter`.
SignedDistanceGrid build_distance_grid(const TriangleMesh& avatar, double voxel_size,
                                       Interrupter& interrupter = null_interrupter(),
                                       double exterior_band = kDistanceBand);

/// Shrinks the normalized avatar until it is certified free of the garment.
/// @param grid the avatar's signed distance (build_distance_grid); read in levelset mode
///        only. When the shrink needs to erode deeper than its band, a full-depth grid is
///        built for it (ShrinkResult::full_depth_grid).
/// @param skin_weights #joints × #avatar vertices, or empty (skeleton mode only).
/// @param pullback skeleton mode: the first pullback tried (SkeletonShrinkOptions); unset:
///        its default.
/// @param interrupter sees the shrink's stages (and a full-depth grid's) and may stop it.
/// @throw InputError in skeleton mode without skeletons; std::invalid_argument in levelset
///        mode without a grid; NoValidShrinkError when no shrink is found; Interrupted from
///        `interrupter`.
ShrinkResult shrink_avatar(ShrinkMode mode, const NormalizedScene& scene,
                           const Eigen::MatrixXd& skin_weights, const SignedDistanceGrid* grid,
                           Interrupter& interrupter = null_interrupter(),
                           std::optional<double> pullback = {});

/// After a failed shrink: writes the most shrunk avatar tried, `error.closest()`, as
/// `dir`/closest_shrunk_avatar.obj (the avatar's faces and materials, positions in the
/// garment's frame so that it lies over the input garment), and returns the report part
/// naming it and the garment and avatar faces (input ids, 0-based) that still cross.
/// Returns null when the error holds no avatar.
/// @param record_dir the folder as the report names it (the staging folder is `dir`).
/// @throw OutputError when the file cannot be written.
nlohmann::json write_closest_shrink(const std::string& dir, const std::string& record_dir,
                                    const Scene& scene, const NormalizedScene& normalized,
                                    const NoValidShrinkError& error);

/// Everything `garment-retarget shrink` can be asked.
struct ShrinkRunOptions {
  ScenePaths inputs;  ///< garment and avatar; skeletons and weights for "skeleton"
  std::string out_dir;
  ShrinkMode mode = ShrinkMode::kLevelset;
  double voxel_size = 0.01;  ///< normalized scene units (the body is about 2 tall)
  /// The caller's: told the stages and their progress, and asked whether to stop besides
  /// the limits; null: none. It must outlive the run.
  Interrupter* interrupter = nullptr;
  bool quiet = false;  ///< no progress on stderr
  RunLimits limits;    ///< input sizes, faces, memory and time the run may take
  /// Copy material files and textures that symbolic links lead to outside the OBJ's folder.
  bool allow_external_assets = false;
};

struct ShrinkRunResult {
  /// kCertified: a certified shrunk avatar was written; else kNoValidShrink.
  Outcome status = Outcome::kNoValidShrink;
  std::string avatar_path;  ///< DIR/shrunk_avatar.obj when certified
  std::string report_path;  ///< DIR/report.json, written either way
  std::string message;      ///< one line for the user
  ShrinkResult shrink;
  double grid_seconds = 0.0;  ///< levelset: building the signed distance
};

/// Reads and normalizes the scene, shrinks the avatar (levelset or skeleton mode) until it
/// is certified free of the garment, and writes DIR/shrunk_avatar.obj (the avatar's faces,
/// UVs and materials, positions in the garment's frame and units so it lies over the input
/// garment) and DIR/report.json (mode, depth, times, medial vertices, or the conflict when
/// no shrink was found, with its position in the garment's frame). In skeleton mode without
/// skin weights the avatar is bound first, with bind_skeleton's defaults (report `inferred`).
/// Like retarget, the files are written into a staging folder swapped into place at the end
/// (ResultFolder); a run that found no shrink keeps an earlier result at DIR.previous.
/// @throw InputError for bad inputs (skeleton mode without skeletons, a non-positive voxel
///        size, inputs beyond options.limits), OutputError when out_dir cannot be written or
///        another run holds it, Interrupted at the limits, a stop request or from
///        options.interrupter.
ShrinkRunResult run_shrink(const ShrinkRunOptions& options);

}  // namespace gr
