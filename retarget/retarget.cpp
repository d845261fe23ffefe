#include "retarget/retarget.hpp"

#include <algorithm>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <optional>

#include <fmt/format.h>
#include <tbb/global_control.h>

#include "core/common/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "core/io/formats/mesh_formats.hpp"
#include "garment/repairs/inherited_crossings.hpp"
#include "retarget/animation/animation_clips.hpp"
#include "retarget/result_page.hpp"
#include "retarget/run/output_folder.hpp"
#include "retarget/run/progress.hpp"
#include "retarget/stage_reports.hpp"
#include "retarget/stages/solve_stage.hpp"
#include "shrink/level_set/grid_distance_field.hpp"

namespace gr {

namespace fs = std::filesystem;

namespace {

/// Where the written garments are: as written into the staging folder, and as the report
/// and certificate name them (their final place).
struct WrittenFiles {
  std::vector<std::string> staged, recorded, meshes;
};

/// One run's surroundings: its limits, result folder, threads, progress and report, and how
/// it ends. The report is the last file of the folder; a run that did not end certified
/// keeps the earlier result aside, so that it cannot be taken for this run's.
class RetargetRun {
 public:
  explicit RetargetRun(const RetargetOptions& options)
      : options_(options), control_(options.limits.timeout_seconds, options.limits.max_memory_mb),
        folder_(checked_out_dir(options), input_files(options.inputs), options.write_in_place),
        progress_(options.quiet, &control_), out_(folder_.staging()) {
    if (options.threads > 0)
      thread_limit_.emplace(tbb::global_control::max_allowed_parallelism,
                            static_cast<std::size_t>(options.threads));
    RetargetReport& report = result_.report;
    report.quality = options.quality;
    report.parameters = parameters_for_quality(options.quality);
    options.overrides.apply_to(report.parameters);
  }

  RetargetReport& report() { return result_.report; }
  Progress& progress() { return progress_; }
  const fs::path& out() const { return out_; }

  RetargetResult finish(Outcome status, std::string message,
                        const std::function<void()>& before_commit = {}) {
    RetargetReport& report = result_.report;
    const bool written_and_certified = certified(status);
    result_.status = status;
    result_.message = std::move(message);
    result_.report_path = folder_.final_path("report.json");
    if (!written_and_certified && folder_.has_previous())
      report.previous_result = folder_.previous_path();
    report.warnings = progress_.warnings();
    report.seconds.total = total_.seconds();
    report.peak_memory_mb = peak_memory_mb();
    const nlohmann::json json = to_json(report);
    write_file_atomically((out_ / "report.json").string(),
                          [&](std::ostream& out) { out << std::setw(2) << json << '\n'; });
    if (before_commit) before_commit();
    folder_.commit(!written_and_certified);
    return result_;
  }

  /// The shrink found no avatar free of the garment: the closest one tried is written.
  RetargetResult no_valid_shrink(const NoValidShrinkError& e, const ShrinkInput& input,
                                 ShrinkMode mode) {
    const Scene& scene = input.scene;
    const NormalizedScene& normalized = input.normalized;
    result_.report.shrink.conflict =
        write_closest_shrink(out_.string(), options_.out_dir, scene, normalized, e);
    const Vector3d where = normalized.normalization.garment_to_scene.invert(e.conflict().position);
    return finish(
        Outcome::kNoValidShrink,
        fmt::format("no valid shrink: {} (near ({:.6g}, {:.6g}, {:.6g}) in the "
                    "garment's frame){}",
                    e.what(), where.x(), where.y(), where.z(), pierced_cause(input, mode)));
  }

  /// Inferred no-fit lists are written into the folder: the report names their final place.
  void record_inferred_files() {
    InferenceReport& inferred = result_.report.inferred;
    if (!inferred.no_fit_inferred) return;
    std::vector<std::string>& per_layer = inferred.no_fit_layer_paths;
    if (per_layer.empty()) inferred.no_fit_path = folder_.final_path("no-fit.txt");
    for (std::string& path : per_layer)
      path = folder_.final_path(fs::path(path).filename().string());
    progress_.log(
        "no-fit", "inferred ({}): {} vertices, {} faces free, written to {}",
        inferred.no_fit.method, inferred.no_fit.vertices.size(), inferred.no_fit_faces,
        per_layer.empty() ? inferred.no_fit_path : fmt::format("{}", fmt::join(per_layer, ", ")));
  }

  /// Writes each inflation round's garment and avatar into frames/ (--frames).
  FrameWriter frame_writer(const Scene& scene, const NormalizedScene& normalized) const {
    if (!options_.frames) return {};
    const fs::path dir = out_ / "frames";
    return [dir, &scene, &normalized](const std::string& name, const MatrixX3d& garment,
                                      const MatrixX3d& avatar) {
      fs::create_directories(dir);
      write_garment_obj((dir / (name + "_garment.obj")).string(), scene, normalized, garment);
      write_avatar_obj((dir / (name + "_avatar.obj")).string(), scene, normalized, avatar);
    };
  }

  WrittenFiles written_files(const WriteOutput& written) {
    WrittenFiles files;
    for (const WrittenGarment& garment : written.garments) {
      files.staged.push_back((out_ / garment.file_name).string());
      files.recorded.push_back(folder_.final_path(garment.file_name));
      files.meshes.push_back(garment.mesh);
    }
    result_.garment_path =
        written.file_name.empty() ? files.recorded.front() : folder_.final_path(written.file_name);
    return files;
  }

  /// Ends a run whose garment was written and checked: certified, and within the shape
  /// thresholds or not; the pages come last, beside the report.
  RetargetResult finish_checked(const Scene& scene, const Normalization& normalization,
                                const CertifyOutput& certified) {
    const RetargetReport& report = result_.report;
    std::string summary = certify_summary(certified.certificate, report, total_.seconds());
    if (report.animation)
      for (const AnimationReport& clip : report.animation->clips)
        summary += "; " + clip_summary(clip.written);
    progress_.log("certify", "{}", summary);
    Outcome status = report.certified() ? Outcome::kCertified : Outcome::kNotCertified;
    const ShapeThresholds& thresholds = report.certify.shape_thresholds;
    bool shape_changed = !shape_violations(report.certify.shape, thresholds).empty();
    for (const ShapeChange& layer : certified.layer_shapes)
      shape_changed = shape_changed || !shape_violations(layer, thresholds).empty();
    if (report.certified() && shape_changed) {
      status = Outcome::kShapeChanged;
      summary += "; SHAPE CHANGED beyond its thresholds";
    }
    return finish(status, summary, [&]() {
      write_retarget_pages(out_.string(), options_.png, scene, normalization, certified.certificate,
                           report);
    });
  }

 private:
  /// The output folder, once the input files passed their checks (before it is created).
  static const std::string& checked_out_dir(const RetargetOptions& options) {
    check_input_files(options.inputs, options.limits.max_input_mb);
    return options.out_dir;
  }

  const RetargetOptions& options_;
  RunControl control_;
  ResultFolder folder_;
  std::optional<tbb::global_control> thread_limit_;
  Progress progress_;
  const fs::path out_;
  RetargetResult result_;
  const StageTimer total_;
};

/// --animation plays skinned glTF files: refused before the solve where the run could not
/// write them, or where a clip cannot be found.
void check_animation_request(const RetargetOptions& options) {
  if (options.animations.empty()) return;
  const MeshFormat& written =
      options.format ? *options.format : mesh_format_for_path(options.inputs.garment);
  if (!written.skinned || !mesh_format_for_path(options.inputs.avatar).skinned)
    throw InputError(options.inputs.avatar, 0,
                     "--animation needs a glTF avatar with a skin and a skinned output "
                     "(--format glb)");
  choose_clips(options.animations, options.inputs.avatar, options.fps);
}

}  // namespace

RetargetResult run_retarget(const RetargetOptions& options) {
  check_animation_request(options);
  RetargetRun run(options);
  RetargetReport& report = run.report();
  Progress& progress = run.progress();
  const RetargetParameters& parameters = report.parameters.solver;

  ReadOutput read = run_read(
      {options.inputs}, {options.limits, options.shrink_mode, options.pose, options.pose_skinning},
      progress);
  if (options.write_posed && read.pose.posed)
    write_obj((run.out() / "posed-garment.obj").string(), read.scene.garment_document,
              read.scene.garment_document.positions);
  Scene& scene = read.scene;
  const std::vector<int> given_order = resolve_layer_order(scene, options.layer_order);
  mark_skirts(scene, options.skirt, options.skirt_layers);
  const PrepareOutput prepared =
      run_prepare({scene, options.inputs},
                  {std::min(parameters.dhat, parameters.fit_support()), given_order}, progress);
  const NormalizedScene& normalized = prepared.normalized;
  const InferOutput inferred = run_infer(
      {scene, normalized, options.inputs, read.shrink_mode},
      {options.inference, options.fit_mode, run.out().string(), report.parameters.voxel_size},
      progress);
  scene.no_fit = inferred.no_fit;
  record_inputs(report, read, prepared, inferred);
  run.record_inferred_files();

  const ShrinkInput shrink_input{scene, normalized, inferred.skin_weights, prepared.pierced};
  const ShrinkOptions shrink_options{read.shrink_mode, report.parameters.voxel_size,
                                     report.ease.distance_band, report.parameters.skeleton_pullback,
                                     options.open_pierced_faces};
  ShrinkOutput shrink = run_shrink(shrink_input, shrink_options, progress);
  record_shrink(report, shrink, inferred);
  if (shrink.failure) return run.no_valid_shrink(*shrink.failure, shrink_input, read.shrink_mode);
  const GridDistanceField distance_field(shrink.grid);
  const SolveOutput solved = run_solve(
      {scene, normalized, prepared.inherited, shrink_input, shrink_options, distance_field,
       inferred, run.frame_writer(scene, normalized), options.shape_thresholds},
      shrink, report, progress);
  if (solved.failure) return run.finish(solved.failure->first, solved.failure->second);
  const MatrixX3d& garment = solved.fit.fit.garment;

  const WriteOutput written =
      run_write({scene, normalized, garment, shrink.pierced_faces, distance_field,
                 inferred.bound_skin_weights(), run.out().string()},
                {options.format, options.split, options.allow_external_assets,
                 options.skin_transfer, parameters.dhat},
                progress);
  record_written(report, written);
  const WrittenFiles files = run.written_files(written);
  const SourceEase* source_ease = report.ease.source_known ? &inferred.source_ease : nullptr;
  const CertifyOutput certified =
      run_certify({options.inputs, scene, normalized, garment, solved.solver.fit_faces, source_ease,
                   files.staged, files.recorded, files.meshes, report},
                  {options.shape_thresholds, options.quality, parameters.dhat}, progress);
  write_certificate((run.out() / "certificate.json").string(), certified.certificate);
  record_certified(report, certified);
  if (scene.layers.size() > 1) {
    const OutfitOutput outfit = run_outfit(
        {scene, normalized, garment, inferred.source_body ? &*inferred.source_body : nullptr,
         certified.certificate, tangled_faces(normalized.garment, prepared.inherited),
         run.out().string(), options.out_dir},
        {given_order, options.write_avatar, parameters.dhat, {}}, progress);
    record_outfit(report, outfit.report, scene, written, files.recorded, certified);
  }
  if (!options.animations.empty() && report.certified())
    report.animation = run_animate(
        {files.staged, files.meshes, options.inputs.avatar, options.inputs.avatar_meshes},
        {options.animations, options.fps, parameters}, progress);
  return run.finish_checked(scene, normalized.normalization, certified);
}

}  // namespace gr
