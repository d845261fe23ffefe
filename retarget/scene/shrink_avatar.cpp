#include "retarget/scene/shrink_avatar.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/common/errors.hpp"
#include "core/common/stopwatch.hpp"
#include "core/io/atomic_file.hpp"
#include "retarget/run/output_folder.hpp"
#include "retarget/scene/inferred_inputs.hpp"
#include "retarget/scene/normalization.hpp"
#include "shrink/level_set/signed_distance_grid.hpp"
#include "shrink/shrunk_avatar/levelset_shrink.hpp"
#include "shrink/shrunk_avatar/skeleton_shrink.hpp"
#include "validate/checks/mesh_intersections.hpp"

namespace gr {

namespace {

nlohmann::json point_json(const Vector3d& p) { return {p.x(), p.y(), p.z()}; }

void require_skeletons_for(ShrinkMode mode, bool has_skeletons, const std::string& avatar_path) {
  if (mode == ShrinkMode::kSkeleton && !has_skeletons)
    throw InputError(avatar_path, 0,
                     "skeleton shrink needs --source-skeleton and --target-skeleton");
}

void check_options(const ShrinkRunOptions& options, const Scene& scene) {
  if (!(options.voxel_size > 0.0) || !std::isfinite(options.voxel_size))
    throw InputError("", 0, "voxel size must be a positive number (normalized units)");
  require_skeletons_for(options.mode, scene.source_skeleton.has_value(), options.inputs.avatar);
}

/// Prints each stage's progress on stderr in steps of a tenth, and passes everything on.
class StderrProgress final : public ForwardingInterrupter {
 public:
  using ForwardingInterrupter::ForwardingInterrupter;
  void start(const std::string& stage) override {
    stage_ = stage;
    next().start(stage);
  }
  void progress(double fraction) override {
    const int tenth = static_cast<int>(fraction * 10.0);
    if (stage_ != printed_stage_ || tenth != printed_tenth_) {
      std::fprintf(stderr, "shrink: %s %3d%%\n", stage_.c_str(), tenth * 10);
      printed_stage_ = stage_;
      printed_tenth_ = tenth;
    }
    next().progress(fraction);
  }

 private:
  std::string stage_;
  std::string printed_stage_;
  int printed_tenth_ = -1;
};

/// What `garment-retarget shrink` hands to its work: the caller's interrupter sees the
/// stages and progress and may stop it first; then the run's limits, whose stop names the
/// command's one stage ("during shrink").
class ShrinkRunInterrupter final : public ForwardingInterrupter {
 public:
  ShrinkRunInterrupter(Interrupter& caller, const RunControl& control)
      : ForwardingInterrupter(caller), control_(control) {}

  std::optional<Interrupted> interruption() const override {
    if (std::optional<Interrupted> stop = next().interruption()) return stop;
    return control_.interruption();
  }

 private:
  const RunControl& control_;
};

}  // namespace

const char* to_string(ShrinkMode mode) {
  switch (mode) {
    case ShrinkMode::kLevelset: return "levelset";
    case ShrinkMode::kSkeleton: return "skeleton";
  }
  return "unknown";
}

ShrinkMode parse_shrink_mode(const std::string& name) {
  for (const ShrinkMode mode : {ShrinkMode::kLevelset, ShrinkMode::kSkeleton})
    if (name == to_string(mode)) return mode;
  throw InputError("", 0, fmt::format("unknown shrink mode '{}' (levelset or skeleton)", name));
}

SignedDistanceGrid build_distance_grid(const TriangleMesh& avatar, double voxel_size,
                                       Interrupter& interrupter, double exterior_band) {
  SignedDistanceOptions options;
  options.exterior_band = std::max(kDistanceBand, exterior_band);
  options.full_depth = false;
  options.interrupter = &interrupter;
  return build_signed_distance(avatar, voxel_size, options);
}

ShrinkResult shrink_avatar(ShrinkMode mode, const NormalizedScene& scene,
                           const Eigen::MatrixXd& skin_weights, const SignedDistanceGrid* grid,
                           Interrupter& interrupter, std::optional<double> pullback) {
  if (mode == ShrinkMode::kLevelset) {
    if (!grid)
      throw std::invalid_argument("the level-set shrink needs the avatar's signed distance");
    LevelsetShrinkOptions options;
    options.interrupter = &interrupter;
    try {
      return shrink_levelset(scene.avatar, scene.garment, *grid, options);
    } catch (const ShrinkBandTooShallowError&) {
      if (grid->full_depth()) throw;
    }
    SignedDistanceOptions full;
    full.exterior_band = kDistanceBand;
    full.interrupter = &interrupter;
    ShrinkResult result =
        shrink_levelset(scene.avatar, scene.garment,
                        build_signed_distance(scene.avatar, grid->voxel_size(), full), options);
    result.full_depth_grid = true;
    return result;
  }
  require_skeletons_for(mode, scene.source_skeleton.has_value(), "");
  SkeletonShrinkOptions options;
  if (pullback) options.pullback = *pullback;
  options.interrupter = &interrupter;
  return shrink_to_skeleton(scene.avatar, scene.garment, *scene.source_skeleton,
                            *scene.target_skeleton, skin_weights, options);
}

nlohmann::json write_closest_shrink(const std::string& dir, const std::string& record_dir,
                                    const Scene& scene, const NormalizedScene& normalized,
                                    const NoValidShrinkError& error) {
  const MatrixX3d& closest = error.closest();
  if (closest.rows() != normalized.avatar.vertices.rows()) return nullptr;
  const Similarity& garment_frame = normalized.normalization.garment_to_scene;
  const Similarity& avatar_frame = normalized.normalization.avatar_to_scene;
  const MatrixX3d positions = export_positions(
      scene.avatar_document, scene.avatar, garment_frame.invert_rows(closest),
      [&](const Vector3d& x) { return garment_frame.invert(avatar_frame.apply(x)); });
  const std::string name = "closest_shrunk_avatar.obj";
  copy_material_files(scene.avatar_document, dir);
  write_obj((std::filesystem::path(dir) / name).string(), scene.avatar_document, positions);
  std::set<int> garment_faces, avatar_faces;
  for (const FacePair& p : find_intersecting_face_pairs(
                               TriangleMesh{closest, normalized.avatar.faces}, normalized.garment)
                               .pairs) {
    avatar_faces.insert(scene.avatar.face_to_obj[static_cast<std::size_t>(p.first)]);
    garment_faces.insert(scene.garment.face_to_obj[static_cast<std::size_t>(p.second)]);
  }
  return {{"closest_shrunk_avatar", (std::filesystem::path(record_dir) / name).string()},
          {"frame", "the garment file's frame and units, over the input garment"},
          {"crossing_garment_faces", garment_faces},
          {"crossing_avatar_faces", avatar_faces}};
}

ShrinkRunResult run_shrink(const ShrinkRunOptions& options) {
  const Stopwatch stopwatch;
  RunControl control(options.limits.timeout_seconds, options.limits.max_memory_mb);
  control.start("shrink");
  check_input_files(options.inputs, options.limits.max_input_mb);
  ResultFolder folder(options.out_dir, input_files(options.inputs));
  const Scene scene = load_scene(options.inputs);
  check_options(options, scene);
  require_within_limits(scene, options.limits);
  StderrProgress stderr_progress(or_null(options.interrupter));
  ShrinkRunInterrupter interrupter(options.quiet ? or_null(options.interrupter) : stderr_progress,
                                   control);
  const NormalizedScene normalized = make_normalized_scene(scene);
  const Normalization& normalization = normalized.normalization;
  const TriangleMesh& avatar = normalized.avatar;

  ShrinkRunResult run;
  const std::filesystem::path out = folder.staging();
  run.report_path = folder.final_path("report.json");
  nlohmann::json report;
  auto write_report_and_commit = [&]() {
    report["seconds"] = stopwatch.seconds();
    if (run.status != Outcome::kCertified && folder.has_previous())
      report["previous_result"] = folder.previous_path();
    write_file_atomically((out / "report.json").string(),
                          [&](std::ostream& os) { os << std::setw(2) << report << '\n'; });
    folder.commit(run.status != Outcome::kCertified);
  };
  report = {{"mode", to_string(options.mode)},
            {"avatar", options.inputs.avatar},
            {"garment", options.inputs.garment},
            {"units",
             "depth and voxel_size in normalized scene units (body about 2 tall); "
             "positions in the garment file's frame"},
            {"garment_units_per_normalized_unit", 1.0 / normalization.garment_to_scene.scale}};
  try {
    control.check();
    if (options.mode == ShrinkMode::kLevelset) {
      const Stopwatch grid_stopwatch;
      const SignedDistanceGrid grid = build_distance_grid(avatar, options.voxel_size, interrupter);
      run.grid_seconds = grid_stopwatch.seconds();
      run.shrink = shrink_avatar(options.mode, normalized, scene.skin_weights, &grid, interrupter);
      report["voxel_size"] = options.voxel_size;
      report["grid_seconds"] = run.grid_seconds;
      report["grid_active_voxels"] = grid.active_voxel_count();
      report["grid_bytes"] = grid.memory_bytes();
      report["full_depth_grid"] = run.shrink.full_depth_grid;
    } else {
      InferenceReport inferred;
      InferenceOptions inference;
      inference.binding_options.interrupter = &interrupter;
      const Eigen::MatrixXd weights =
          skin_weights_for_shrink(scene, normalized, inference, inferred);
      inferred.binding_options.interrupter = nullptr;
      report["inferred"] = to_json(inferred)["skin_weights"];
      run.shrink = shrink_avatar(options.mode, normalized, weights, nullptr, interrupter);
      report["pullback"] = run.shrink.pullback;
      report["collapsed_vertices"] = run.shrink.collapsed_vertices;
      report["collapse_rounds"] = run.shrink.collapse_rounds;
    }
  } catch (const NoValidShrinkError& e) {
    const ShrinkConflict& conflict = e.conflict();
    const Vector3d where = normalization.garment_to_scene.invert(conflict.position);
    run.message = fmt::format("{} [in the garment's frame: ({:.6g}, {:.6g}, {:.6g})]", e.what(),
                              where.x(), where.y(), where.z());
    report["found"] = false;
    report["closest"] = write_closest_shrink(out.string(), options.out_dir, scene, normalized, e);
    report["conflict"] = {
        {"kind", conflict.kind == ShrinkConflict::Kind::kSurfacesCross ? "surfaces cross"
                                                                       : "garment inside avatar"},
        {"avatar_face", conflict.avatar_face},
        {"garment_face", conflict.garment_face},
        {"garment_vertex", conflict.garment_vertex},
        {"count", conflict.count},
        {"position", point_json(where)},
        {"message", run.message}};
    write_report_and_commit();
    return run;
  }

  // Back to the garment's frame: the shrunk avatar lies over the garment as given.
  const Similarity& garment_frame = normalization.garment_to_scene;
  const Similarity& avatar_frame = normalization.avatar_to_scene;
  const MatrixX3d positions = export_positions(
      scene.avatar_document, scene.avatar, garment_frame.invert_rows(run.shrink.vertices),
      [&](const Vector3d& x) { return garment_frame.invert(avatar_frame.apply(x)); });
  run.avatar_path = folder.final_path("shrunk_avatar.obj");
  const std::vector<std::string> warnings =
      copy_material_files(scene.avatar_document, out.string(), options.allow_external_assets);
  if (!warnings.empty()) report["warnings"] = warnings;
  write_obj((out / "shrunk_avatar.obj").string(), scene.avatar_document, positions);

  run.status = Outcome::kCertified;
  report["found"] = true;
  report["depth"] = run.shrink.depth;
  report["depth_garment_units"] = run.shrink.depth / garment_frame.scale;
  report["medial_vertices"] = run.shrink.medial_vertices;
  report["avatar_vertices"] = avatar.vertices.rows();
  report["certifications"] = run.shrink.certifications;
  report["shrink_seconds"] = run.shrink.seconds;
  write_report_and_commit();
  run.message = options.mode == ShrinkMode::kLevelset
                    ? fmt::format(
                          "shrunk avatar certified free of the garment at depth {:.4g} "
                          "({} vertices in the medial region)",
                          run.shrink.depth, run.shrink.medial_vertices)
                    : fmt::format(
                          "shrunk avatar certified free of the garment on the source "
                          "skeleton (pullback {:.3g}, {} vertices pulled toward joints)",
                          run.shrink.pullback, run.shrink.collapsed_vertices);
  return run;
}

}  // namespace gr
