#include "retarget/retarget.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <optional>

#include <fmt/format.h>
#include <tbb/global_control.h>

#include "core/io/atomic_file.hpp"
#include "garment/repairs/inherited_crossings.hpp"
#include "retarget/result_page.hpp"
#include "retarget/run/output_folder.hpp"
#include "retarget/run/progress.hpp"
#include "retarget/stages/certify_stage.hpp"
#include "retarget/stages/fit_stage.hpp"
#include "retarget/stages/infer_stage.hpp"
#include "retarget/stages/inflate_stage.hpp"
#include "retarget/stages/normalize_stage.hpp"
#include "retarget/stages/outfit_stage.hpp"
#include "retarget/stages/proxy_stage.hpp"
#include "retarget/stages/read_stage.hpp"
#include "retarget/stages/shrink_stage.hpp"
#include "retarget/stages/solver_scene.hpp"
#include "retarget/stages/write_stage.hpp"
#include "shrink/level_set/grid_distance_field.hpp"

namespace gr {

namespace fs = std::filesystem;

namespace {

/// When the inflation fails from a skeleton-shrunk avatar, it runs again from one shrunk
/// with this fraction of its pullback.
constexpr double kStalledPullbackFactor = 0.2;
/// When the inflation stalls from every shrink, it runs once more with a barrier this many
/// times wider.
constexpr double kStalledBarrierFactor = 2.0;
/// A stalled inflation whose tangle pairs lie closer than this fraction of dhat is jammed at
/// a crossing the input came with: the barrier there is overpowered.
constexpr double kPressedGap = 0.01;

void write_report(const std::string& path, const RetargetReport& report) {
  const nlohmann::json json = to_json(report);
  write_file_atomically(path, [&](std::ostream& out) { out << std::setw(2) << json << '\n'; });
}

/// Writes each inflation round's garment and avatar into `dir` (--frames).
FrameWriter frame_writer(const fs::path& dir, const Scene& scene,
                         const NormalizedScene& normalized) {
  return [dir, &scene, &normalized](const std::string& name, const MatrixX3d& garment,
                                    const MatrixX3d& avatar) {
    fs::create_directories(dir);
    write_garment_obj((dir / (name + "_garment.obj")).string(), scene, normalized, garment);
    write_avatar_obj((dir / (name + "_avatar.obj")).string(), scene, normalized, avatar);
  };
}

/// The report parts of the read, normalize and infer stages.
void record_inputs(RetargetReport& report, const ReadOutput& read, const NormalizeOutput& normalize,
                   const InferOutput& inferred) {
  report.estimated_memory_mb = read.estimated_memory_mb;
  report.shrink.mode = read.shrink_mode;
  report.seconds.read = read.seconds;
  report.normalize = normalize.report;
  report.seconds.normalize = normalize.seconds;
  report.inferred = inferred.inferred;
  report.ease = inferred.ease;
}

/// The shrink's report part (its time with the binding's).
void record_shrink(RetargetReport& report, const ShrinkOutput& shrink,
                   const InferOutput& inferred) {
  const nlohmann::json conflict = report.shrink.conflict;
  report.shrink = shrink.report;
  report.shrink.conflict = conflict;
  report.seconds.shrink = inferred.binding_seconds + shrink.seconds;
}

/// What the solver models, from the first solve on (the scope may widen in a solve).
void record_modelled(RetargetReport& report, const SolverScene& solver) {
  const RetargetParameters& parameters = report.parameters.solver;
  report.fit.fit_faces =
      static_cast<int>(std::count(solver.fit_faces.begin(), solver.fit_faces.end(), true));
  report.fit.avatar_faces_modelled = solver.avatar_faces_modelled;
  report.fit.self_contact = parameters.self_contact;
  report.fit.self_contact_everywhere = parameters.self_contact_everywhere;
}

/// The certify stage's report part, and the clearance where the solver saw no pair.
void record_certified(RetargetReport& report, const CertifyOutput& certified) {
  report.certify = certified.report;
  report.seconds.certify = certified.seconds;
  if (report.ease.source_known) {
    report.ease.measure = certified.ease;
    report.ease.document_ratio = certified.ease_document_ratio;
  }
  report.normalize.inherited.still_crossing = certified.inherited_still_crossing;
  // The solver sees only pairs within dhat; a garment that ended further away takes the
  // certificate's clearance, so the report never holds an infinity.
  if (!std::isfinite(report.fit.min_distance))
    report.fit.min_distance =
        certified.certificate.validation.result.totals().smallest_avatar_clearance *
        report.normalize.scene_scale;
}

/// The outfit's report part: the stage's, with each layer's own files and shape.
void record_outfit(RetargetReport& report, OutfitReport outfit, const Scene& scene,
                   const WriteOutput& written, const std::vector<std::string>& recorded_paths,
                   const CertifyOutput& certified) {
  for (std::size_t k = 0; k < scene.layers.size(); ++k) {
    const GarmentLayer& layer = scene.layers[k];
    outfit.layers.push_back({layer.name, layer.path, layer.mesh, layer.face_count,
                             recorded_paths[k], written.garments[k].mesh,
                             certified.layer_shapes[k]});
  }
  report.seconds.certify += outfit.seconds;
  report.outfit = std::move(outfit);
}

std::string no_valid_shrink_message(const NoValidShrinkError& e, const Scene& scene,
                                    const NormalizedScene& normalized, ShrinkMode mode) {
  const Vector3d where = normalized.normalization.garment_to_scene.invert(e.conflict().position);
  return fmt::format("no valid shrink: {} (near ({:.6g}, {:.6g}, {:.6g}) in the garment's frame){}",
                     e.what(), where.x(), where.y(), where.z(),
                     pierced_cause(scene, normalized, mode));
}

/// What the solve needs from the stages before it.
struct SolveInput {
  const Scene& scene;
  const NormalizedScene& normalized;
  const InheritedCrossings& inherited;
  const ShrinkInput& shrink_input;
  const ShrinkOptions& shrink_options;
  const DistanceField& distance_field;  ///< the shrink's grid
  const InferOutput& inferred;
  FrameWriter frames;  ///< empty: no frames
};

/// The solved garment, or how the solve failed.
struct Solved {
  std::optional<std::pair<Outcome, std::string>> failure;
  SolverScene solver;
  FitOutput fit;
};

/// Inflate, then fit. After an inflation that stalled from a skeleton shrink, the avatar is
/// shrunk thinner (`shrink` replaced) and inflated once more: a thinner avatar leaves the
/// garment more room between body parts.
Solved solve_garment(const SolveInput& in, ShrinkOutput& shrink, RetargetReport& report,
                     Progress& progress) {
  const RetargetParameters& parameters = report.parameters.solver;
  Solved solved;
  SolverScene& solver = solved.solver;
  const auto solver_scene = [&]() {
    solver = make_solver_scene({in.scene, in.normalized, shrink.shrunk.vertices, in.distance_field,
                                in.inherited, shrink.pierced_faces},
                               parameters);
    record_modelled(report, solver);
  };
  const auto inflate = [&](const InflationGuide& guide) {
    InflateOutput inflated = run_inflate({solver}, {parameters, in.frames, guide}, progress);
    add_inflation_attempt(report.inflate, inflated.report);
    record_modelled(report, solver);
    report.seconds.inflate += inflated.seconds;
    progress.log("inflate", "{} ({:.2f} s)", inflated.inflation.message, report.seconds.inflate);
    return inflated.inflation;
  };
  solver_scene();
  const bool ease_fit = report.ease.fit == FitMode::kEase;
  const SourceEase* source_ease = ease_fit ? &in.inferred.source_ease : nullptr;
  int largest_layer_faces = 0;
  if (in.scene.layers.size() > 1) {
    std::vector<int> layer_faces(in.scene.layers.size(), 0);
    for (const int layer : layer_of_garment_faces(in.scene))
      ++layer_faces[static_cast<std::size_t>(layer)];
    largest_layer_faces = *std::max_element(layer_faces.begin(), layer_faces.end());
  }
  ProxyOutput proxy =
      run_proxy({solver, source_ease, largest_layer_faces},
                {parameters, report.parameters.proxy_faces, report.ease.max_offset}, progress);
  report.proxy = proxy.report;
  report.seconds.proxy = proxy.report.seconds;
  // A retry below solves the garment directly: the proxy's paths lead where it failed.
  InflationResult inflation = inflate(proxy.paths ? proxy.paths->inflation() : InflationGuide());
  report.proxy.inflate_path = inflation.guide;
  const auto stalled = [&] {
    return !inflation.succeeded() && inflation.status != InflationStatus::kSolverFailure;
  };
  // Layers and pieces pressed together by the growing avatar (a trouser cuff inside a
  // shoe) can jam in a barrier thinner than their gap to each other: a wider one keeps
  // them apart earlier, so that they move together.
  double& dhat = report.parameters.solver.dhat;
  const double first_dhat = dhat;
  const auto inflate_wider = [&](const std::string& why) {
    progress.warn(
        fmt::format("the inflation stalled with dhat {:.3g}{}: inflating again with "
                    "a barrier twice as wide (--dhat {:.3g})",
                    dhat, why, kStalledBarrierFactor * dhat));
    dhat *= kStalledBarrierFactor;
    solver_scene();
    inflation = inflate({});
  };
  // A crossing the input came with cannot slide: jammed there, the garment needs the wider
  // barrier first, before a thinner avatar.
  if (stalled()) {
    const int pressed = pressed_tangle_pairs(solver.scene, parameters, inflation.garment,
                                             kPressedGap * parameters.dhat);
    if (pressed > 0)
      inflate_wider(
          fmt::format(", {} pairs pressed together at crossings the input came with", pressed));
  }
  if (stalled() && in.shrink_options.mode == ShrinkMode::kSkeleton) {
    // The thinner avatar is tried in the barrier the garment first stalled in, then in the
    // wider one below, whichever came first.
    dhat = first_dhat;
    const double pullback = kStalledPullbackFactor * shrink.shrunk.pullback;
    const std::string no_thinner =
        run_thinner_shrink(in.shrink_input, in.shrink_options, pullback, shrink, progress);
    // The shrunk avatar is what failed: one the garment can escape from does not exist.
    if (!no_thinner.empty()) {
      solved.failure = {Outcome::kNoValidShrink,
                        fmt::format("the inflation from the skeleton shrink (pullback {:.3g}) "
                                    "failed: {}; and no thinner shrink is free of the garment: {}",
                                    shrink.shrunk.pullback, inflation.message, no_thinner)};
      return solved;
    }
    record_shrink(report, shrink, in.inferred);
    solver_scene();
    inflation = inflate({});
  }
  if (stalled() && dhat == first_dhat) inflate_wider("");
  if (!inflation.succeeded()) {
    solved.failure = {Outcome::kSolverFailure,
                      "inflation failed: " + inflation.message +
                          "; allow more work with --max-al-rounds and --max-newton-iterations, or "
                          "widen the barrier with --dhat"};
    return solved;
  }
  // A garment whose inflation left the proxy's path starts its fit away from where the
  // proxy's did: held back wherever the two differ, the fit's path would only crumple it.
  const bool guided = proxy.paths && inflation.guide.points > 0 && inflation.guide.reached_end;
  solved.fit = run_fit({solver, inflation.garment, source_ease},
                       {parameters, report.ease.max_offset,
                        guided ? proxy.paths->fit(inflation.garment) : GuidePath()},
                       progress);
  report.proxy.fit_path = solved.fit.fit.guide;
  if (solved.fit.ease_targets) report.ease.targets = std::move(*solved.fit.ease_targets);
  report.fit = solved.fit.report;
  record_modelled(report, solver);
  report.seconds.fit = solved.fit.seconds;
  const NewtonResult& solve = solved.fit.fit.solve;
  if (solve.status == SolverStatus::kNonFiniteEnergy || !std::isfinite(solve.gradient_norm))
    solved.failure = {Outcome::kSolverFailure, "fit failed: " + solve.message};
  return solved;
}

}  // namespace

RetargetResult run_retarget(const RetargetOptions& options) {
  RunControl control(options.limits.timeout_seconds, options.limits.max_memory_mb);
  check_input_files(options.inputs, options.limits.max_input_mb);
  ResultFolder folder(options.out_dir, input_files(options.inputs), options.write_in_place);
  std::optional<tbb::global_control> thread_limit;
  if (options.threads > 0)
    thread_limit.emplace(tbb::global_control::max_allowed_parallelism,
                         static_cast<std::size_t>(options.threads));
  Progress progress(options.quiet, &control);
  const fs::path out = folder.staging();
  RetargetResult result;
  RetargetReport& report = result.report;
  report.quality = options.quality;
  report.parameters = parameters_for_quality(options.quality);
  options.overrides.apply_to(report.parameters);
  const RetargetParameters& parameters = report.parameters.solver;
  const StageTimer total;
  // The report is the last file of the folder; a run that did not end certified keeps the
  // earlier result aside, so that it cannot be taken for this run's.
  const auto finish = [&](Outcome status, std::string message,
                          const std::function<void()>& before_commit = {}) {
    const bool written_and_certified = certified(status);
    result.status = status;
    result.message = std::move(message);
    if (!written_and_certified && folder.has_previous())
      report.previous_result = folder.previous_path();
    report.warnings = progress.warnings();
    report.seconds.total = total.seconds();
    report.peak_memory_mb = peak_memory_mb();
    write_report((out / "report.json").string(), report);
    if (before_commit) before_commit();
    folder.commit(!written_and_certified);
    return result;
  };

  ReadOutput read = run_read({options.inputs}, {options.limits, options.shrink_mode}, progress);
  Scene& scene = read.scene;
  result.report_path = folder.final_path("report.json");
  const std::vector<int> given_order = resolve_layer_order(scene, options.layer_order);
  mark_skirts(scene, options.skirt, options.skirt_layers);
  const NormalizeOutput normalized_scene = run_normalize(
      {scene, options.inputs}, {std::min(parameters.dhat, parameters.fit_support())}, progress);
  const NormalizedScene& normalized = normalized_scene.normalized;
  double& min_separation = report.parameters.solver.ccd.min_separation;
  min_separation = std::max(min_separation, normalized_scene.ccd_min_separation);
  const InferOutput inferred = run_infer(
      {scene, normalized, options.inputs, read.shrink_mode},
      {options.inference, options.fit_mode, out.string(), report.parameters.voxel_size}, progress);
  scene.no_fit = inferred.no_fit;
  record_inputs(report, read, normalized_scene, inferred);
  if (report.inferred.no_fit_inferred) {
    std::vector<std::string>& per_layer = report.inferred.no_fit_layer_paths;
    if (per_layer.empty()) report.inferred.no_fit_path = folder.final_path("no-fit.txt");
    for (std::string& path : per_layer)
      path = folder.final_path(fs::path(path).filename().string());
    progress.log("no-fit", "inferred ({}): {} vertices, {} faces free, written to {}",
                 report.inferred.no_fit.method, report.inferred.no_fit.vertices.size(),
                 report.inferred.no_fit_faces,
                 per_layer.empty() ? report.inferred.no_fit_path
                                   : fmt::format("{}", fmt::join(per_layer, ", ")));
  }
  // Skin weights bound to the target skeleton when none were given: the shrink's, and a
  // written GLB's skin.
  const Eigen::MatrixXd bound_skin_weights =
      report.inferred.skin_weights_inferred ? inferred.skin_weights : Eigen::MatrixXd();

  const ShrinkInput shrink_input{scene, normalized, inferred.skin_weights};
  const ShrinkOptions shrink_options{read.shrink_mode, report.parameters.voxel_size,
                                     report.ease.distance_band, report.parameters.skeleton_pullback,
                                     options.open_pierced_faces};
  ShrinkOutput shrink = run_shrink(shrink_input, shrink_options, progress);
  record_shrink(report, shrink, inferred);
  if (shrink.failure) {
    report.shrink.conflict =
        write_closest_shrink(out.string(), options.out_dir, scene, normalized, *shrink.failure);
    return finish(Outcome::kNoValidShrink,
                  no_valid_shrink_message(*shrink.failure, scene, normalized, read.shrink_mode));
  }
  const GridDistanceField distance_field(shrink.grid);
  const FrameWriter frames =
      options.frames ? frame_writer(out / "frames", scene, normalized) : FrameWriter();
  Solved solved = solve_garment({scene, normalized, normalized_scene.inherited, shrink_input,
                                 shrink_options, distance_field, inferred, frames},
                                shrink, report, progress);
  if (solved.failure) return finish(solved.failure->first, solved.failure->second);
  const SolverScene& solver = solved.solver;
  const FitResult& fit = solved.fit.fit;

  const WriteOutput written =
      run_write({scene, normalized, fit.garment, shrink.pierced_faces, distance_field,
                 bound_skin_weights, out.string()},
                {options.format, options.split, options.allow_external_assets,
                 options.skin_transfer, parameters.dhat},
                progress);
  report.shrink.pierced.opened_document_faces = written.opened_document_faces;
  report.skin = written.skin;
  report.seconds.write = written.seconds;
  std::vector<std::string> written_files;
  std::vector<std::string> recorded_paths;
  std::vector<std::string> written_meshes;
  for (const WrittenGarment& garment : written.garments) {
    written_files.push_back((out / garment.file_name).string());
    recorded_paths.push_back(folder.final_path(garment.file_name));
    written_meshes.push_back(garment.mesh);
  }
  result.garment_path =
      written.file_name.empty() ? recorded_paths.front() : folder.final_path(written.file_name);

  const CertifyOutput certified_output =
      run_certify({options.inputs, scene, normalized, fit.garment, solver.fit_faces,
                   report.ease.source_known ? &inferred.source_ease : nullptr, written_files,
                   recorded_paths, written_meshes, report},
                  {options.shape_thresholds, options.quality, parameters.dhat}, progress);
  const Certificate& certificate = certified_output.certificate;
  write_certificate((out / "certificate.json").string(), certificate);
  record_certified(report, certified_output);
  if (scene.layers.size() > 1) {
    OutfitOutput outfit = run_outfit(
        {scene, normalized, fit.garment, inferred.source_body ? &*inferred.source_body : nullptr,
         certificate, tangled_faces(normalized.garment, normalized_scene.inherited), out.string(),
         options.out_dir},
        {given_order, options.write_avatar, parameters.dhat, {}}, progress);
    record_outfit(report, outfit.report, scene, written, recorded_paths, certified_output);
  }
  std::string summary = certify_summary(certificate, report, total.seconds());
  progress.log("certify", "{}", summary);
  Outcome status = report.certified() ? Outcome::kCertified : Outcome::kNotCertified;
  const ShapeThresholds& thresholds = report.certify.shape_thresholds;
  bool shape_changed = !shape_violations(report.certify.shape, thresholds).empty();
  for (const ShapeChange& layer : certified_output.layer_shapes)
    shape_changed = shape_changed || !shape_violations(layer, thresholds).empty();
  if (report.certified() && shape_changed) {
    status = Outcome::kShapeChanged;
    summary += "; SHAPE CHANGED beyond its thresholds";
  }
  return finish(status, summary, [&]() {
    write_retarget_pages(out.string(), options.png, scene, normalized.normalization, certificate,
                         report);
  });
}

}  // namespace gr
