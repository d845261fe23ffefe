#include "tools/pipeline/retarget.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <optional>

#include <fmt/format.h>
#include <tbb/global_control.h>

#include "core/common/errors.hpp"
#include "core/fit/garment_fit.hpp"
#include "core/inflation/avatar_inflation.hpp"
#include "core/io/atomic_file.hpp"
#include "shrink/level_set/grid_distance_field.hpp"
#include "shrink/level_set/signed_distance_grid.hpp"
#include "shrink/shrunk_avatar/levelset_shrink.hpp"
#include "shrink/shrunk_avatar/skeleton_shrink.hpp"
#include "validate/certify/certificate.hpp"
#include "validate/checks/self_intersections.hpp"
#include "validate/report/file_digest.hpp"
#include "tools/pipeline/contact_scope.hpp"
#include "tools/pipeline/normalization.hpp"
#include "tools/pipeline/output_folder.hpp"
#include "tools/pipeline/progress.hpp"
#include "tools/pipeline/result_page.hpp"

namespace gr {

namespace fs = std::filesystem;

namespace {

/// How far outside the avatar the signed-distance grid holds distances (normalized units):
/// the fit pulls garment points only from within it.
constexpr double kFitBand = 0.1;

/// Newton progress lines: the first steps, then every tenth.
constexpr int kNewtonLogEvery = 10;
/// A boundary loop further than this (in lengths of its bone) from its place along the bone
/// on the written garment is reported: the loops of a fitted garment sit within a few
/// thousandths of theirs.
constexpr double kLoopOffsetWarning = 0.03;

/// Rejects a garment that crosses itself as given (`self`, found on its normalized copy):
/// no solver output could be certified.
void require_garment_free_of_itself(const Scene& scene, const SelfIntersections& self) {
  if (self.pairs.count == 0) return;
  const auto& pair = self.pairs.pairs.front();
  const auto& face_to_obj = scene.garment.face_to_obj;
  throw InputError(
      scene.garment_document.source_path, 0,
      fmt::format("garment intersects itself ({} face pairs, e.g. faces {} and {}); an "
                  "intersecting garment cannot be certified",
                  self.pairs.count, face_to_obj[static_cast<std::size_t>(pair.first)] + 1,
                  face_to_obj[static_cast<std::size_t>(pair.second)] + 1));
}

std::vector<bool> fit_face_mask(const TriangleMesh& garment, const std::vector<int>& no_fit) {
  std::vector<bool> listed(static_cast<std::size_t>(garment.vertices.rows()), false);
  for (const int v : no_fit) listed[static_cast<std::size_t>(v)] = true;
  std::vector<bool> fit(static_cast<std::size_t>(garment.faces.rows()), true);
  for (Eigen::Index f = 0; f < garment.faces.rows(); ++f)
    fit[static_cast<std::size_t>(f)] = !(listed[static_cast<std::size_t>(garment.faces(f, 0))] &&
                                         listed[static_cast<std::size_t>(garment.faces(f, 1))] &&
                                         listed[static_cast<std::size_t>(garment.faces(f, 2))]);
  return fit;
}

void write_report(const std::string& path, const RetargetReport& report) {
  const nlohmann::json json = to_json(report);
  write_file_atomically(path, [&](std::ostream& out) { out << std::setw(2) << json << '\n'; });
}

/// Writes a garment (normalized #Vg×3) as an OBJ in the avatar's frame and units.
void write_garment(const std::string& path, const Scene& scene, const Normalization& n,
                   const Eigen::Ref<const MatrixX3d>& garment) {
  const MatrixX3d positions = export_positions(
      scene.garment_document, scene.garment, n.avatar_to_scene.invert_rows(garment),
      [&](const Vector3d& p) { return n.avatar_to_scene.invert(n.garment_to_scene.apply(p)); });
  write_obj(path, scene.garment_document, positions);
}

void write_avatar(const std::string& path, const Scene& scene, const Normalization& n,
                  const Eigen::Ref<const MatrixX3d>& avatar) {
  const MatrixX3d positions =
      export_positions(scene.avatar_document, scene.avatar, n.avatar_to_scene.invert_rows(avatar),
                       [](const Vector3d& p) { return p; });
  write_obj(path, scene.avatar_document, positions);
}

const char* status_name(SolverStatus status) { return to_string(status); }

}  // namespace

RetargetResult run_retarget(const RetargetOptions& options) {
  const Progress progress(options.quiet);
  std::optional<tbb::global_control> thread_limit;
  if (options.threads > 0)
    thread_limit.emplace(tbb::global_control::max_allowed_parallelism,
                         static_cast<std::size_t>(options.threads));

  RetargetResult result;
  RetargetReport& report = result.report;
  report.quality = options.quality;
  report.parameters = parameters_for_quality(options.quality);
  options.overrides.apply_to(report.parameters);
  const PipelineParameters& parameters = report.parameters;
  const StageTimer total;

  // Read.
  StageTimer stage;
  const Scene scene = load_scene(options.inputs);
  const bool has_skeletons = scene.source_skeleton.has_value();
  report.shrink_mode = options.shrink_mode.empty() ? (has_skeletons ? "skeleton" : "levelset")
                                                   : options.shrink_mode;
  if (report.shrink_mode == "skeleton" && !has_skeletons)
    throw InputError(options.inputs.avatar, 0,
                     "skeleton shrink needs --source-skeleton and --target-skeleton");
  prepare_output_folder(options.out_dir);
  const fs::path out(options.out_dir);
  result.report_path = (out / "report.json").string();
  report.seconds.read = stage.seconds();

  // Normalize.
  stage = StageTimer();
  NormalizedScene normalized =
      make_normalized_scene(scene, lattice_spacing(std::min(parameters.solver.dhat,
                                                            parameters.solver.fit_support())));
  // Rounding to the lattice can fold a sliver or close a hairline gap: keep the exact
  // coordinates then, and refuse the garment only if it crosses itself as given.
  SelfIntersections self = find_self_intersecting_face_pairs(normalized.garment, 1);
  if (self.pairs.count > 0 && normalized.lattice > 0.0) {
    normalized = make_normalized_scene(scene);
    self = find_self_intersecting_face_pairs(normalized.garment, 1);
  }
  require_garment_free_of_itself(scene, self);
  const Normalization& frames = normalized.normalization;
  report.scene_scale = frames.avatar_to_scene.scale;
  report.lattice = normalized.lattice;
  // Progress starts once the inputs are known good, so bad input prints its error alone.
  progress.log("read", "{} on {}", options.inputs.garment, options.inputs.avatar);
  for (const auto& warning : scene.warnings) {
    progress.log("warning", "{}", warning);
    report.warnings.push_back(warning);
  }
  report.garment_vertices = static_cast<int>(normalized.garment.vertices.rows());
  report.garment_faces = static_cast<int>(normalized.garment.faces.rows());
  report.avatar_faces_total = static_cast<int>(normalized.avatar.faces.rows());
  report.seconds.normalize = stage.seconds();
  progress.log("scene", "garment {} vertices / {} faces, avatar {} faces, scale {:.6g}",
               report.garment_vertices, report.garment_faces, report.avatar_faces_total,
               report.scene_scale);

  auto finish = [&](RetargetStatus status, std::string message) {
    result.status = status;
    result.message = std::move(message);
    report.seconds.total = total.seconds();
    report.peak_memory_mb = peak_memory_mb();
    write_report(result.report_path, report);
    return result;
  };

  // Shrink.
  stage = StageTimer();
  SignedDistanceOptions grid_options;
  grid_options.exterior_band = kFitBand;
  // The level-set shrink walks to any depth; the fit needs only the band near the surface.
  grid_options.full_depth = report.shrink_mode == "levelset";
  const SignedDistanceGrid grid =
      build_signed_distance(normalized.avatar, parameters.voxel_size, grid_options);
  const GridDistanceField distance_field(grid);
  progress.log("shrink", "signed distance: {} voxels of {:.4g} in {:.2f} s",
               grid.active_voxel_count(), parameters.voxel_size, stage.seconds());
  ShrinkResult shrunk;
  try {
    if (report.shrink_mode == "levelset")
      shrunk = shrink_levelset(normalized.avatar, normalized.garment, grid);
    else
      shrunk = shrink_to_skeleton(normalized.avatar, normalized.garment, *normalized.source_skeleton,
                                  *normalized.target_skeleton, scene.skin_weights);
  } catch (const NoValidShrinkError& e) {
    const Vector3d where = frames.garment_to_scene.invert(e.conflict().position);
    report.seconds.shrink = stage.seconds();
    return finish(RetargetStatus::kNoValidShrink,
                  fmt::format("no valid shrink: {} (near ({:.6g}, {:.6g}, {:.6g}) in the garment's "
                              "frame)",
                              e.what(), where.x(), where.y(), where.z()));
  }
  report.shrink_depth = shrunk.depth;
  report.shrink_medial_vertices = shrunk.medial_vertices;
  report.seconds.shrink = stage.seconds();
  progress.log("shrink", "{} shrink certified free of the garment in {:.2f} s",
               report.shrink_mode, report.seconds.shrink);

  // The solver's view of the scene.
  GarmentScene problem_scene;
  problem_scene.garment = normalized.garment;
  problem_scene.avatar = normalized.avatar;
  problem_scene.shrunk_avatar = shrunk.vertices;
  const double largest_avatar_motion =
      (normalized.avatar.vertices - shrunk.vertices).rowwise().norm().maxCoeff();
  const double scope_margin = largest_avatar_motion + kFitBand + parameters.solver.dhat;
  problem_scene.avatar_faces_used =
      reachable_avatar_faces(normalized.garment.vertices, shrunk.vertices,
                             normalized.avatar.vertices, normalized.avatar.faces, scope_margin);
  report.avatar_faces_modelled = static_cast<int>(problem_scene.avatar_faces_used.size());
  // Every face in reach is every face: nothing a solve could leave, so no second solve.
  if (report.avatar_faces_modelled == report.avatar_faces_total)
    problem_scene.avatar_faces_used.clear();
  if (has_skeletons)
    problem_scene.skeletons = SkeletonMotion{normalized.source_skeleton->joints,
                                             normalized.target_skeleton->joints,
                                             normalized.target_skeleton->bones, options.skirt};
  problem_scene.no_fit = scene.no_fit;
  problem_scene.distance_field = &distance_field;
  const std::vector<bool> fit_faces = fit_face_mask(normalized.garment, scene.no_fit);
  report.fit_faces = static_cast<int>(std::count(fit_faces.begin(), fit_faces.end(), true));
  report.self_contact = parameters.solver.self_contact;
  report.self_contact_everywhere = parameters.solver.self_contact_everywhere;
  report.terms = {"surface", "contact"};
  if (has_skeletons) report.terms.push_back("position");
  report.terms.push_back("fit");

  const fs::path frames_dir = out / "frames";
  if (options.frames) {
    fs::create_directories(frames_dir);
    write_garment((frames_dir / "round_00_garment.obj").string(), scene, frames, normalized.garment.vertices);
    write_avatar((frames_dir / "round_00_avatar.obj").string(), scene, frames, shrunk.vertices);
  }

  // Inflate.
  stage = StageTimer();
  const char* solving = "inflate";
  auto on_newton = [&](const NewtonProgress& step) {
    if (step.iteration <= 3 || step.iteration % kNewtonLogEvery == 0)
      progress.log(solving, "  Newton {:4d}  E {:.9g}  step {:.3g}  |g| {:.3g}", step.iteration,
                   step.energy, step.step, step.gradient_norm);
  };
  auto on_round = [&](const InflationRound& round) {
    progress.log("inflate", "round {:2d}: t {:.9f}  eta {:.3g}  lambda1 {:.3g}  {} Newton steps{}{}",
                 round.round, round.t, round.eta, round.lambda1, round.solve.iterations,
                 round.reset ? "  (overshoot: reset)" : "", round.snapped ? "  snap to t = 1 valid" : "");
    if (!options.frames) return;
    const auto name = fmt::format("round_{:02d}", round.round);
    write_garment((frames_dir / (name + "_garment.obj")).string(), scene, frames, round.garment);
    const MatrixX3d avatar_now = shrunk.vertices + round.t * (normalized.avatar.vertices - shrunk.vertices);
    write_avatar((frames_dir / (name + "_avatar.obj")).string(), scene, frames, avatar_now);
  };
  // A solve that carried the garment beyond the modelled avatar faces may have passed
  // through one it did not see: it runs again with every face (rare, so the price is fine).
  auto widen_scope_if_left = [&](const MatrixX3d& garment, const char* stage_name,
                                 const char* what) {
    if (problem_scene.avatar_faces_used.empty() ||
        within_contact_scope(normalized.garment.vertices, garment, scope_margin,
                             parameters.solver.dhat))
      return false;
    problem_scene.avatar_faces_used.clear();
    report.avatar_faces_modelled = report.avatar_faces_total;
    const std::string note = fmt::format(
        "the {} carried the garment beyond the modelled avatar faces; solved again with all {}",
        what, report.avatar_faces_total);
    progress.log(stage_name, "{}", note);
    report.warnings.push_back(note);
    return true;
  };
  InflationResult inflation = inflate_avatar(problem_scene, parameters.solver, on_round, on_newton);
  if (inflation.succeeded() && widen_scope_if_left(inflation.garment, "inflate", "inflation"))
    inflation = inflate_avatar(problem_scene, parameters.solver, on_round, on_newton);
  report.al_rounds = inflation.rounds;
  report.al_resets = inflation.resets;
  report.inflate_newton_iterations = inflation.newton_iterations;
  report.inflate_fold_free = inflation.fold_free_fraction;
  report.inflate_status = to_string(inflation.status);
  report.seconds.inflate = stage.seconds();
  progress.log("inflate", "{} ({:.2f} s)", inflation.message, report.seconds.inflate);
  if (!inflation.succeeded())
    return finish(RetargetStatus::kSolverFailure,
                  "inflation failed: " + inflation.message +
                      "; allow more work with --max-al-rounds and --max-newton-iterations, or "
                      "widen the barrier with --dhat");

  // Fit.
  stage = StageTimer();
  solving = "fit";
  FitResult fit = fit_garment(problem_scene, inflation.garment, parameters.solver, on_newton);
  if (fit.solve.status != SolverStatus::kNonFiniteEnergy && widen_scope_if_left(fit.garment, "fit", "fit"))
    fit = fit_garment(problem_scene, inflation.garment, parameters.solver, on_newton);
  report.fit_newton_iterations = fit.solve.iterations;
  report.fit_fold_free = fit.fold_free_fraction;
  report.fit_status = status_name(fit.solve.status);
  report.seconds.fit = stage.seconds();
  progress.log("fit", "{} after {} Newton steps ({:.2f} s)", fit.solve.message, fit.solve.iterations,
               report.seconds.fit);
  if (fit.solve.status == SolverStatus::kNonFiniteEnergy)
    return finish(RetargetStatus::kSolverFailure, "fit failed: " + fit.solve.message);
  // A fit stopped early is still intersection free (every step was CCD-bounded): the
  // garment is written and certified, and the report says the fit is incomplete.
  if (!fit.solve.converged()) {
    const std::string warning = "fit stopped before its tolerance: " + fit.solve.message +
                                "; allow more steps with --max-newton-iterations or loosen --eps-tol";
    progress.log("warning", "{}", warning);
    report.warnings.push_back(warning);
  }
  {
    GarmentProblem final_problem(problem_scene, parameters.solver, GarmentProblem::Stage::kFit);
    const Eigen::VectorXd x = final_problem.layout().pack(1.0, fit.garment);
    // minimum_distance finds the contact pairs at x first; the contact term needs them.
    report.min_distance = final_problem.minimum_distance(x);
    report.final_energies = final_problem.term_values(x);
    report.loop_offsets = final_problem.loop_offsets(x);
    for (std::size_t loop = 0; loop < report.loop_offsets.size(); ++loop) {
      if (report.loop_offsets[loop] <= kLoopOffsetWarning) continue;
      const std::string warning = fmt::format(
          "boundary loop {} ({} vertices) ends {:.0f}% of its bone's length from its place along "
          "the bone: it may be caught on the avatar and the garment stretched around it",
          loop, final_problem.loop_bones()[loop].vertices.size(), 100.0 * report.loop_offsets[loop]);
      progress.log("warning", "{}", warning);
      report.warnings.push_back(warning);
    }
    const auto& faces = normalized.garment.faces;
    double rest_area = 0.0;
    for (Eigen::Index f = 0; f < faces.rows(); ++f) {
      const Vector3d a = normalized.garment.vertices.row(faces(f, 0)).transpose();
      const Vector3d b = normalized.garment.vertices.row(faces(f, 1)).transpose();
      const Vector3d c = normalized.garment.vertices.row(faces(f, 2)).transpose();
      rest_area += 0.5 * (b - a).cross(c - a).norm();
    }
    report.surface_energy_per_area = report.final_energies["surface"] / rest_area;
  }

  // Write.
  stage = StageTimer();
  result.garment_path = (out / "garment.obj").string();
  for (const auto& warning : copy_material_files(scene.garment_document, options.out_dir))
    report.warnings.push_back(warning);
  write_garment(result.garment_path, scene, frames, fit.garment);
  report.seconds.write = stage.seconds();

  // Certify the file as written.
  stage = StageTimer();
  nlohmann::json extra = {
      {"inputs",
       {{"garment", {{"path", options.inputs.garment}, {"sha256", sha256_of_file(options.inputs.garment)}}},
        {"avatar", {{"path", options.inputs.avatar}, {"sha256", sha256_of_file(options.inputs.avatar)}}}}},
      {"output", {{"path", result.garment_path}, {"sha256", sha256_of_file(result.garment_path)}}},
      {"parameters", to_json(report)["parameters"]},
      {"quality", options.quality}};
  const Certificate certificate = certify_garment(result.garment_path, options.inputs.avatar, extra);
  write_certificate((out / "certificate.json").string(), certificate);
  report.certified = certificate.certified();
  report.seconds.certify = stage.seconds();

  // Measure.
  const TriangleMesh written_garment{frames.avatar_to_scene.invert_rows(fit.garment),
                                     normalized.garment.faces};
  report.fit_error = measure_fit_error(written_garment, fit_faces, scene.avatar.mesh);
  report.distortion =
      measure_distortion(normalized.garment.vertices, fit.garment, normalized.garment.faces);

  const auto totals = certificate.validation.result.totals();
  // The solver sees only pairs within dhat; a garment that ended further away takes the
  // certificate's clearance, so the report never holds an infinity.
  if (!std::isfinite(report.min_distance))
    report.min_distance = totals.smallest_avatar_clearance * report.scene_scale;
  const std::string summary = fmt::format(
      "{}: {} garment-avatar and {} self intersections; min distance {:.3g} (avatar units); fit "
      "error mean {:.3g}, p95 {:.3g}; {:.1f} s",
      report.certified ? "certified" : "NOT certified", totals.garment_avatar_intersections,
      totals.garment_self_intersections, report.min_distance / report.scene_scale,
      report.fit_error.mean, report.fit_error.p95, total.seconds());
  progress.log("certify", "{}", summary);
  RetargetResult done = finish(report.certified ? RetargetStatus::kCertified : RetargetStatus::kNotCertified,
                               summary);
  write_retarget_pages(options.out_dir, options.png, scene, frames, certificate, done.report);
  return done;
}

}  // namespace gr
