#include "tools/pipeline/retarget.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <limits>
#include <optional>
#include <set>

#include <fmt/format.h>
#include <tbb/global_control.h>

#include "core/common/errors.hpp"
#include "core/energies/fit_energy.hpp"
#include "core/fit/garment_fit.hpp"
#include "core/inflation/avatar_inflation.hpp"
#include "core/io/atomic_file.hpp"
#include "core/skeleton/skin_matching.hpp"
#include "shrink/level_set/grid_distance_field.hpp"
#include "shrink/level_set/signed_distance_grid.hpp"
#include "tools/pipeline/contact_scope.hpp"
#include "tools/pipeline/inherited_crossings.hpp"
#include "tools/pipeline/normalization.hpp"
#include "tools/pipeline/output_folder.hpp"
#include "tools/pipeline/pierced_faces.hpp"
#include "tools/pipeline/progress.hpp"
#include "tools/pipeline/result_page.hpp"
#include "validate/certify/certificate.hpp"
#include "validate/checks/self_intersections.hpp"
#include "validate/report/file_digest.hpp"

namespace gr {

namespace fs = std::filesystem;

namespace {

/// Newton progress lines: the first steps, then every tenth.
constexpr int kNewtonLogEvery = 10;
/// A boundary loop further than this (in lengths of its bone) from its place along the bone
/// on the written garment is reported: the loops of a fitted garment sit within a few
/// thousandths of theirs.
constexpr double kLoopOffsetWarning = 0.03;

/// What every stage reads and writes: the options, the progress lines and the result whose
/// report each stage fills in.
struct Run {
  Run(const RetargetOptions& run_options, const ResultFolder& result_folder,
      const RunControl& run_control)
      : options(run_options), folder(result_folder), control(run_control),
        progress(run_options.quiet), out(result_folder.staging()) {}

  const RetargetOptions& options;
  const ResultFolder& folder;
  const RunControl& control;
  Progress progress;
  RetargetResult result;
  /// Where the run writes (the staging folder); reports record folder.final_path().
  fs::path out;
  std::string staged(const std::string& name) const { return (out / name).string(); }

  RetargetReport& report() { return result.report; }
  const PipelineParameters& parameters() const { return result.report.parameters; }
  void warn(const std::string& warning) {
    progress.log("warning", "{}", warning);
    result.report.warnings.push_back(warning);
  }
};

/// The scene as read, and in normalized units.
struct Inputs {
  Scene scene;
  NormalizedScene normalized;
  /// Skin weights bound to the target skeleton when none were given (#J×#avatar welded
  /// vertices); empty otherwise. The shrink uses them, and a written GLB's skin too.
  Eigen::MatrixXd bound_skin_weights;
  /// Where the garment crosses itself as given (normalized garment's faces).
  InheritedCrossings inherited;
  /// Garment faces left out of the avatar contact (the avatar passes through them as
  /// given), sorted rows of the normalized garment's faces.
  std::vector<int> pierced_faces;
};

/// The scene a shrunk avatar must be free of: the garment without its pierced faces.
NormalizedScene shrink_scene(const Inputs& in) {
  NormalizedScene scene = in.normalized;
  if (!in.pierced_faces.empty()) scene.garment = surface_without(scene.garment, in.pierced_faces);
  return scene;
}

/// Neighbourhood of an inherited crossing whose self pairs are not modelled, in edge rings
/// around each crossing face: one ring leaves pairs a fraction of an edge from the
/// crossing line inside the barrier at the start.
constexpr int kTangleRings = 2;

/// Pierced faces (RetargetOptions::open_pierced_faces) grow by this many edge rings: the
/// shrunk avatar around a bone is a little thicker than the bone.
constexpr int kPiercedRings = 2;
/// Shrinks tried, each leaving out the faces the closest one met, before giving up; and the
/// largest share of the garment's faces left out (more means the garment is not around
/// the body the skeleton gives).
constexpr int kPiercedShrinks = 4;
constexpr double kMaxPiercedFraction = 0.25;

void write_report(const std::string& path, const RetargetReport& report) {
  const nlohmann::json json = to_json(report);
  write_file_atomically(path, [&](std::ostream& out) { out << std::setw(2) << json << '\n'; });
}

/// Writes a garment (normalized #Vg×3) as an OBJ in the avatar's frame and units.
void write_garment(const std::string& path, const Inputs& in,
                   const Eigen::Ref<const MatrixX3d>& garment) {
  const Normalization& n = in.normalized.normalization;
  const MatrixX3d positions = export_positions(
      in.scene.garment_document, in.scene.garment, n.avatar_to_scene.invert_rows(garment),
      [&](const Vector3d& p) { return n.avatar_to_scene.invert(n.garment_to_scene.apply(p)); });
  write_obj(path, in.scene.garment_document, positions);
}

/// Writes an avatar (normalized #Va×3) as an OBJ in its file's frame and units.
void write_avatar(const std::string& path, const Inputs& in,
                  const Eigen::Ref<const MatrixX3d>& avatar) {
  const Normalization& n = in.normalized.normalization;
  const MatrixX3d positions =
      export_positions(in.scene.avatar_document, in.scene.avatar,
                       n.avatar_to_scene.invert_rows(avatar), [](const Vector3d& p) { return p; });
  write_obj(path, in.scene.avatar_document, positions);
}

double surface_area(const TriangleMesh& mesh) {
  double area = 0.0;
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    const Vector3d a = mesh.vertices.row(mesh.faces(f, 0)).transpose();
    const Vector3d b = mesh.vertices.row(mesh.faces(f, 1)).transpose();
    const Vector3d c = mesh.vertices.row(mesh.faces(f, 2)).transpose();
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  return area;
}

/// Read: the scene's files and the shrink mode.
Scene read_stage(Run& run) {
  const StageTimer timer;
  Scene scene = load_scene(run.options.inputs);
  run.report().estimated_memory_mb = require_within_limits(scene, run.options.limits);
  const bool has_skeletons = scene.source_skeleton.has_value();
  const ShrinkMode mode = run.options.shrink_mode.value_or(has_skeletons ? ShrinkMode::kSkeleton
                                                                         : ShrinkMode::kLevelset);
  if (mode == ShrinkMode::kSkeleton && !has_skeletons)
    throw InputError(run.options.inputs.avatar, 0,
                     "skeleton shrink needs --source-skeleton and --target-skeleton");
  run.report().shrink_mode = mode;
  run.result.report_path = run.folder.final_path("report.json");
  run.report().seconds.read = timer.seconds();
  return scene;
}

/// Normalize: the scene in normalized units, rounded to the lattice where that adds no
/// crossing of the garment with itself; the crossings it has as given are kept as inherited.
NormalizedScene normalize_stage(Run& run, const Scene& scene, InheritedCrossings& inherited) {
  const StageTimer timer;
  RetargetReport& report = run.report();
  const RetargetParameters& solver = run.parameters().solver;
  NormalizedScene normalized =
      make_normalized_scene(scene, lattice_spacing(std::min(solver.dhat, solver.fit_support())));
  require_comparable_sizes(scene, normalized);
  // Rounding to the lattice can fold a sliver or close a hairline gap: keep the exact
  // coordinates when they cross less.
  SelfIntersections self = find_self_intersecting_face_pairs(normalized.garment);
  if (self.pairs.count > 0 && normalized.lattice > 0.0) {
    NormalizedScene exact = make_normalized_scene(scene);
    SelfIntersections exact_self = find_self_intersecting_face_pairs(exact.garment);
    if (exact_self.pairs.count < self.pairs.count) {
      normalized = std::move(exact);
      self = std::move(exact_self);
    }
  }
  // The copies of a split edge lie on their originals: their neighbourhood is a tangle too.
  std::vector<std::vector<int>> split_sites;
  for (const auto& [copy, original] : scene.garment_ties) split_sites.push_back({copy, original});
  inherited =
      tangles_of(normalized.garment, std::move(self.pairs.pairs), kTangleRings, split_sites);
  inherited.attachments =
      attach_crossing_pieces(normalized.garment, inherited.pairs, report.inherited.attached_pieces);
  report.split_edges = scene.split_edges;
  report.split_copies = static_cast<int>(scene.garment_ties.size());
  InheritedReport& kept = report.inherited;
  kept.pairs = static_cast<int>(inherited.pairs.size());
  kept.tangles = inherited.tangle_count;
  kept.tangled_vertices = inherited.tangled_vertices;
  kept.document_pairs.clear();
  const auto& face_to_obj = scene.garment.face_to_obj;
  for (const FacePair& p : inherited.pairs) {
    const int a = face_to_obj[static_cast<std::size_t>(p.first)];
    const int b = face_to_obj[static_cast<std::size_t>(p.second)];
    kept.document_pairs.push_back({std::min(a, b), std::max(a, b)});
  }
  report.scene_scale = normalized.normalization.avatar_to_scene.scale;
  report.lattice = normalized.lattice;
  // The solver sees the avatar rounded to the lattice, the certificate the avatar as given.
  // Rounding moves a point of the avatar by at most half a lattice cell's diagonal, so
  // pairs kept a whole diagonal apart stay apart on both (a pair may otherwise creep,
  // a fraction of its gap per CCD-bounded step, to well below the rounding).
  double& min_separation = report.parameters.solver.ccd.min_separation;
  min_separation = std::max(min_separation, std::sqrt(3.0) * normalized.lattice);
  // Progress starts once the inputs are known good, so bad input prints its error alone.
  run.progress.log("read", "{} on {}", run.options.inputs.garment, run.options.inputs.avatar);
  for (const auto& warning : scene.warnings) run.warn(warning);
  if (kept.pairs > 0)
    run.warn(fmt::format(
        "the garment crosses itself as given ({} face pairs, e.g. faces {} and {}, 1-based): the "
        "crossings are kept as inherited, their {} vertices around them left out of self "
        "contact, and the certificate counts only new ones",
        kept.pairs, kept.document_pairs.front().first + 1, kept.document_pairs.front().second + 1,
        kept.tangled_vertices));
  report.garment_vertices = static_cast<int>(normalized.garment.vertices.rows());
  report.garment_faces = static_cast<int>(normalized.garment.faces.rows());
  report.avatar_faces_total = static_cast<int>(normalized.avatar.faces.rows());
  report.seconds.normalize = timer.seconds();
  run.progress.log("scene", "garment {} vertices / {} faces, avatar {} faces, scale {:.6g}",
                   report.garment_vertices, report.garment_faces, report.avatar_faces_total,
                   report.scene_scale);
  return normalized;
}

/// The ease fit reads the avatar's distance this far out at most (normalized units): twice
/// the ease of a roomy coat's fitted vertices on the shared source bodies.
constexpr double kMaxEaseBand = 0.3;

/// The fit mode, and the garment's ease on its source body (normalized; null: none given).
/// The distance band the fit reads is widened to reach every target (ease up to twice the
/// largest source ease of a fitted vertex).
SourceEase ease_stage(Run& run, const Inputs& in, const TriangleMesh* body) {
  EaseReport& ease = run.report().ease;
  ease.source_known = body != nullptr;
  ease.fit = run.options.fit_mode.value_or(ease.source_known ? FitMode::kEase : FitMode::kTight);
  const double voxel = run.parameters().voxel_size;
  ease.distance_band = kDistanceBand;
  ease.max_offset = 0.0;
  if (!ease.source_known) {
    if (ease.fit == FitMode::kEase)
      throw InputError(run.options.inputs.garment, 0,
                       "--fit ease needs the garment's source body (--source-body)");
    if (!run.options.fit_mode)
      run.warn(
          "no --source-body: the fit pulls the garment onto the avatar (tight); give the body "
          "the garment was made on to keep its ease");
    return {};
  }
  SourceEase source = measure_source_ease(in.normalized.garment, *body);
  ease.filled_vertices = source.filled;
  if (ease.fit == FitMode::kTight) return source;
  std::vector<bool> listed(source.distance.size(), false);
  for (const int v : in.scene.no_fit) listed[static_cast<std::size_t>(v)] = true;
  double largest = 0.0;
  for (std::size_t v = 0; v < source.distance.size(); ++v)
    if (!listed[v]) largest = std::max(largest, source.distance[v]);
  constexpr double kBandVoxels = 4.0;  // the interpolant reads 2 voxels each side
  ease.distance_band = std::clamp(2.0 * largest + kBandVoxels * voxel, kDistanceBand, kMaxEaseBand);
  ease.max_offset = ease.distance_band - kBandVoxels * voxel;
  run.progress.log("fit",
                   "ease from the source body: largest {:.4g}, {} vertices over cuts, "
                   "distance band {:.3g}",
                   largest, source.filled, ease.distance_band);
  return source;
}

/// The avatar's signed distance near its surface: read by the fit, and by the level-set
/// shrink (which builds a full-depth grid itself when it must erode deeper).
SignedDistanceGrid distance_grid_stage(Run& run, const TriangleMesh& avatar) {
  const StageTimer timer;
  SignedDistanceGrid grid = with_stop_hook(run.control, [&](const ProgressCallback& hook) {
    return build_distance_grid(avatar, run.parameters().voxel_size, hook,
                               run.report().ease.distance_band);
  });
  run.progress.log("shrink", "signed distance: {} voxels of {:.4g} in {:.2f} s",
                   grid.active_voxel_count(), run.parameters().voxel_size, timer.seconds());
  return grid;
}

/// The solver's view of the scene: the avatar faces the garment can reach, the skeletons,
/// the no-fit list and the distance field.
struct SolverScene {
  GarmentScene scene;
  /// Garment motion the contact scope allows for (normalized units).
  double scope_margin = 0.0;
  /// Per garment face, whether it fits (not no-fit).
  std::vector<bool> fit_faces;
};

SolverScene solver_scene_stage(Run& run, const Inputs& in, const ShrinkResult& shrunk,
                               const DistanceField& distance_field) {
  RetargetReport& report = run.report();
  const NormalizedScene& normalized = in.normalized;
  SolverScene solver;
  GarmentScene& scene = solver.scene;
  scene.garment = normalized.garment;
  scene.avatar = normalized.avatar;
  scene.shrunk_avatar = shrunk.vertices;
  const double largest_avatar_motion =
      (normalized.avatar.vertices - shrunk.vertices).rowwise().norm().maxCoeff();
  solver.scope_margin = largest_avatar_motion + kDistanceBand + run.parameters().solver.dhat;
  scene.avatar_faces_used = reachable_avatar_faces(normalized.garment.vertices, shrunk.vertices,
                                                   normalized.avatar.vertices,
                                                   normalized.avatar.faces, solver.scope_margin);
  report.avatar_faces_modelled = static_cast<int>(scene.avatar_faces_used.size());
  // Every face in reach is every face: nothing a solve could leave, so no second solve.
  if (report.avatar_faces_modelled == report.avatar_faces_total) scene.avatar_faces_used.clear();
  if (normalized.source_skeleton)
    scene.skeletons =
        SkeletonMotion{normalized.source_skeleton->joints, normalized.target_skeleton->joints,
                       normalized.target_skeleton->bones, run.options.skirt};
  scene.no_fit = in.scene.no_fit;
  scene.distance_field = &distance_field;
  scene.garment_tangles = in.inherited.tangles;
  scene.faces_without_avatar_contact = in.pierced_faces;
  // Vertices only pierced faces hold are not fitted: nothing keeps them off the body.
  if (!in.pierced_faces.empty()) {
    std::vector<char> kept(static_cast<std::size_t>(normalized.garment.vertices.rows()), 0);
    for (Eigen::Index f = 0; f < normalized.garment.faces.rows(); ++f)
      if (!std::binary_search(in.pierced_faces.begin(), in.pierced_faces.end(),
                              static_cast<int>(f)))
        for (int k = 0; k < 3; ++k)
          kept[static_cast<std::size_t>(normalized.garment.faces(f, k))] = 1;
    for (std::size_t v = 0; v < kept.size(); ++v)
      if (!kept[v]) scene.no_fit.push_back(static_cast<int>(v));
    std::sort(scene.no_fit.begin(), scene.no_fit.end());
    scene.no_fit.erase(std::unique(scene.no_fit.begin(), scene.no_fit.end()), scene.no_fit.end());
  }
  scene.ties = in.scene.garment_ties;
  scene.attachments = in.inherited.attachments;
  solver.fit_faces = fit_face_mask(
      normalized.garment.faces, static_cast<int>(normalized.garment.vertices.rows()), scene.no_fit);
  report.fit_faces =
      static_cast<int>(std::count(solver.fit_faces.begin(), solver.fit_faces.end(), true));
  report.self_contact = run.parameters().solver.self_contact;
  report.self_contact_everywhere = run.parameters().solver.self_contact_everywhere;
  return solver;
}

/// A solve that carried the garment beyond the modelled avatar faces may have passed through
/// one it did not see: widens the scope to every face (the caller solves again; rare, so the
/// price is fine). @return whether it widened.
bool widen_scope_if_left(Run& run, SolverScene& solver, const MatrixX3d& garment,
                         const char* stage_name) {
  GarmentScene& scene = solver.scene;
  if (scene.avatar_faces_used.empty() ||
      within_contact_scope(scene.garment.vertices, garment, solver.scope_margin,
                           run.parameters().solver.dhat))
    return false;
  scene.avatar_faces_used.clear();
  run.report().avatar_faces_modelled = run.report().avatar_faces_total;
  run.progress.log(stage_name, "the {} carried the garment beyond the modelled avatar faces",
                   stage_name);
  run.report().warnings.push_back(fmt::format(
      "the {} carried the garment beyond the modelled avatar faces; solved again with all {}",
      stage_name, run.report().avatar_faces_total));
  return true;
}

/// Newton progress lines for the solve of `stage_name`.
NewtonCallback newton_progress(const Run& run, const char* stage_name) {
  return [&run, stage_name](const NewtonProgress& step) {
    run.control.check(stage_name);
    if (step.iteration <= 3 || step.iteration % kNewtonLogEvery == 0)
      run.progress.log(stage_name, "  Newton {:4d}  E {:.9g}  step {:.3g}  |g| {:.3g}  mu {:.2g}",
                       step.iteration, step.energy, step.step, step.gradient_norm, step.damping);
  };
}

/// The shrink's results in the report (its time added to the stage's), and its line in the
/// progress.
void record_shrink(Run& run, const ShrinkResult& shrunk, double seconds) {
  RetargetReport& report = run.report();
  report.shrink_depth = shrunk.depth;
  report.shrink_medial_vertices = shrunk.medial_vertices;
  report.shrink_full_depth_grid = shrunk.full_depth_grid;
  report.shrink_pullback = shrunk.pullback;
  report.seconds.shrink += seconds;
  run.progress.log("shrink", "{} shrink certified free of the garment in {:.2f} s",
                   to_string(report.shrink_mode), seconds);
}

/// Why a skeleton shrink cannot be free of the garment when its bones pass through garment
/// faces (a closed shell, a capped leg): "; " and the faces and bones, else "".
std::string pierced_cause(const Inputs& in, ShrinkMode mode) {
  if (mode != ShrinkMode::kSkeleton || !in.normalized.source_skeleton) return "";
  const std::vector<FacePair> pierced =
      faces_pierced_by_bones(in.normalized.garment, *in.normalized.source_skeleton);
  if (pierced.empty()) return "";
  return "; " + describe_pierced_faces(pierced, in.scene.garment.face_to_obj,
                                       *in.normalized.source_skeleton, in.scene.joint_names);
}

/// Shrink: the avatar shrunk free of the garment. With RetargetOptions::open_pierced_faces,
/// faces the avatar passes through as given leave the avatar contact: those the source
/// bones pierce (without a skeleton: those the closest shrunk avatar meets), then, while
/// no shrunk avatar is free of the rest, those the closest one meets next to them, each
/// with kPiercedRings rings; up to kPiercedShrinks shrinks and kMaxPiercedFraction of the
/// faces. A garment the bones pierce nowhere is never opened.
/// @throw NoValidShrinkError from the last shrink tried.
ShrinkResult shrink_stage(Run& run, Inputs& in, const Eigen::MatrixXd& skin_weights,
                          const SignedDistanceGrid& grid) {
  RetargetReport& report = run.report();
  const TriangleMesh& garment = in.normalized.garment;
  const auto shrink = [&]() {
    return with_stop_hook(run.control, [&](const ProgressCallback& hook) {
      return shrink_avatar(report.shrink_mode, shrink_scene(in), skin_weights, &grid, hook,
                           run.parameters().skeleton_pullback);
    });
  };
  if (!run.options.open_pierced_faces) return shrink();
  const auto max_faces =
      static_cast<std::size_t>(kMaxPiercedFraction * static_cast<double>(garment.faces.rows()));
  const auto leave_out = [&](const std::vector<int>& seeds) {
    std::vector<int> grown = faces_around(garment, seeds, kPiercedRings);
    std::vector<int> merged;
    std::set_union(in.pierced_faces.begin(), in.pierced_faces.end(), grown.begin(), grown.end(),
                   std::back_inserter(merged));
    if (merged.size() > max_faces) return false;
    in.pierced_faces = std::move(merged);
    return true;
  };
  if (in.normalized.source_skeleton) {
    const Skeleton& skeleton = *in.normalized.source_skeleton;
    const std::vector<FacePair> by_bones = faces_pierced_by_bones(garment, skeleton);
    std::vector<int> seeds;
    std::set<std::string> bones;
    for (const FacePair& p : by_bones) {
      seeds.push_back(p.first);
      const auto joint = [&](int j) {
        return j < static_cast<int>(in.scene.joint_names.size())
                   ? in.scene.joint_names[static_cast<std::size_t>(j)]
                   : fmt::format("joint {}", j);
      };
      bones.insert(joint(skeleton.bones(p.second, 0)) + "-" + joint(skeleton.bones(p.second, 1)));
    }
    report.pierced.bones.assign(bones.begin(), bones.end());
    if (!seeds.empty() && leave_out(seeds))
      run.progress.log("shrink",
                       "{} garment faces pierced by {} source bones: {} left out of "
                       "the avatar contact",
                       by_bones.size(), bones.size(), in.pierced_faces.size());
  }
  for (int attempt = 1;; ++attempt) {
    report.pierced.shrinks = attempt;
    try {
      ShrinkResult shrunk = shrink();
      for (const int f : in.pierced_faces)
        report.pierced.document_faces.push_back(
            in.scene.garment.face_to_obj[static_cast<std::size_t>(f)]);
      return shrunk;
    } catch (const NoValidShrinkError& e) {
      if (attempt == kPiercedShrinks || e.closest().rows() != in.normalized.avatar.vertices.rows())
        throw;
      std::vector<int> met = faces_against_shrunk_avatar(
          TriangleMesh{e.closest(), in.normalized.avatar.faces}, garment);
      // With a skeleton the bones say where the body passes through the garment: only
      // the region around the faces they pierce grows. Without, the closest shrunk avatar
      // (the body's core) says it first.
      if (in.normalized.source_skeleton || !in.pierced_faces.empty()) {
        std::vector<char> near(static_cast<std::size_t>(garment.vertices.rows()), 0);
        for (const int f : in.pierced_faces)
          for (int k = 0; k < 3; ++k) near[static_cast<std::size_t>(garment.faces(f, k))] = 1;
        met.erase(std::remove_if(met.begin(), met.end(),
                                 [&](int f) {
                                   for (int k = 0; k < 3; ++k)
                                     if (near[static_cast<std::size_t>(garment.faces(f, k))])
                                       return false;
                                   return true;
                                 }),
                  met.end());
      }
      const std::size_t before = in.pierced_faces.size();
      if (!leave_out(met) || in.pierced_faces.size() == before) throw;
      run.progress.log("shrink",
                       "no shrink free of the garment: the closest meets {} faces; {} "
                       "left out of the avatar contact, shrinking again",
                       met.size(), in.pierced_faces.size() - before);
    }
  }
}

/// When the inflation fails from a skeleton-shrunk avatar, it runs again from one shrunk
/// with this fraction of its pullback (SkeletonShrinkOptions::pullback: 0.25, then 0.05).
constexpr double kStalledPullbackFactor = 0.2;

/// Inflate: the avatar grows back from A0 to A under barrier contact (Algorithm 1).
InflationResult inflate_stage(Run& run, const Inputs& in, SolverScene& solver) {
  const StageTimer timer;
  const fs::path frames_dir = run.out / "frames";
  const MatrixX3d& shrunk = solver.scene.shrunk_avatar;
  if (run.options.frames) {
    fs::create_directories(frames_dir);
    write_garment((frames_dir / "round_00_garment.obj").string(), in,
                  in.normalized.garment.vertices);
    write_avatar((frames_dir / "round_00_avatar.obj").string(), in, shrunk);
  }
  const auto on_round = [&](const InflationRound& round) {
    run.control.check("inflate");
    run.progress.log(
        "inflate", "round {:2d}: t {:.9f}  eta {:.3g}  lambda1 {:.3g}  {} Newton steps{}{}",
        round.round, round.t, round.eta, round.lambda1, round.solve.iterations,
        round.reset ? "  (overshoot: reset)" : "", round.snapped ? "  snap to t = 1 valid" : "");
    if (!run.options.frames) return;
    const auto name = fmt::format("round_{:02d}", round.round);
    write_garment((frames_dir / (name + "_garment.obj")).string(), in, round.garment);
    write_avatar((frames_dir / (name + "_avatar.obj")).string(), in,
                 shrunk + round.t * (in.normalized.avatar.vertices - shrunk));
  };
  const NewtonCallback on_newton = newton_progress(run, "inflate");
  const RetargetParameters& parameters = run.parameters().solver;
  InflationResult inflation = inflate_avatar(solver.scene, parameters, on_round, on_newton);
  if (inflation.succeeded() && widen_scope_if_left(run, solver, inflation.garment, "inflation"))
    inflation = inflate_avatar(solver.scene, parameters, on_round, on_newton);
  RetargetReport& report = run.report();
  // Added: a second inflation from a thinner shrink counts with the first.
  report.al_rounds += inflation.rounds;
  report.al_resets += inflation.resets;
  report.inflate_newton_iterations += inflation.newton_iterations;
  report.inflate_fold_free = inflation.fold_free_fraction;
  report.inflate_status = to_string(inflation.status);
  report.seconds.inflate += timer.seconds();
  run.progress.log("inflate", "{} ({:.2f} s)", inflation.message, report.seconds.inflate);
  return inflation;
}

/// After a failed inflation from a skeleton-shrunk avatar: shrinks it again with
/// kStalledPullbackFactor of its pullback and inflates once more (a thinner avatar leaves
/// the garment more room between body parts). The report counts both attempts. Leaves
/// everything as it was when no thinner shrunk avatar is free of the garment, and returns
/// why; else returns "".
std::string inflate_from_thinner_shrink(Run& run, const Inputs& in,
                                        const Eigen::MatrixXd& skin_weights,
                                        const SignedDistanceGrid& grid,
                                        const DistanceField& distance_field, ShrinkResult& shrunk,
                                        SolverScene& solver, InflationResult& inflation) {
  RetargetReport& report = run.report();
  const double pullback = kStalledPullbackFactor * shrunk.pullback;
  run.progress.log("inflate", "shrinking the avatar again with pullback {:.3g}", pullback);
  const StageTimer timer;
  ShrinkResult thinner;
  try {
    thinner = with_stop_hook(run.control, [&](const ProgressCallback& hook) {
      return shrink_avatar(report.shrink_mode, shrink_scene(in), skin_weights, &grid, hook,
                           pullback);
    });
  } catch (const NoValidShrinkError& e) {
    return e.what();
  }
  shrunk = std::move(thinner);
  record_shrink(run, shrunk, timer.seconds());
  report.shrink_thinned = true;
  solver = solver_scene_stage(run, in, shrunk, distance_field);
  inflation = inflate_stage(run, in, solver);
  return "";
}

/// Fit: the garment settles onto the body (Step 3), with the end-of-fit measurements in the
/// report.
FitResult fit_stage(Run& run, SolverScene& solver, const MatrixX3d& inflated) {
  const StageTimer timer;
  const NewtonCallback on_newton = newton_progress(run, "fit");
  const RetargetParameters& parameters = run.parameters().solver;
  FitResult fit = fit_garment(solver.scene, inflated, parameters, on_newton);
  if (fit.solve.status != SolverStatus::kNonFiniteEnergy &&
      widen_scope_if_left(run, solver, fit.garment, "fit"))
    fit = fit_garment(solver.scene, inflated, parameters, on_newton);
  RetargetReport& report = run.report();
  report.fit_newton_iterations = fit.solve.iterations;
  report.fit_fold_free = fit.fold_free_fraction;
  report.fit_status = to_string(fit.solve.status);
  report.seconds.fit = timer.seconds();
  run.progress.log("fit", "{} after {} Newton steps ({:.2f} s)", fit.solve.message,
                   fit.solve.iterations, report.seconds.fit);
  if (fit.solve.status == SolverStatus::kNonFiniteEnergy) return fit;
  // A fit stopped early is still intersection free (every step was CCD-bounded): the
  // garment is written and certified, and the report says the fit is incomplete.
  if (!fit.solve.converged())
    run.warn("fit stopped before its tolerance: " + fit.solve.message +
             "; allow more steps with --max-newton-iterations or loosen --eps-tol");
  report.terms = fit.terms;
  report.min_distance = fit.min_distance;
  report.final_energies = fit.energies;
  report.loop_offsets = fit.loop_offsets;
  for (std::size_t loop = 0; loop < fit.loop_offsets.size(); ++loop) {
    if (fit.loop_offsets[loop] <= kLoopOffsetWarning) continue;
    run.warn(fmt::format(
        "boundary loop {} ({} vertices) ends {:.0f}% of its bone's length from its place along "
        "the bone: it may be caught on the avatar and the garment stretched around it",
        loop, fit.loop_sizes[loop], 100.0 * fit.loop_offsets[loop]));
  }
  report.surface_energy_per_area = fit.energies["surface"] / surface_area(solver.scene.garment);
  return fit;
}

/// Weights per welded vertex (#J×#welded) carried to a mesh's document positions (#J×#P)
/// through `obj_to_sim`; positions no face references follow joint 0.
Eigen::MatrixXd on_document_positions(const Eigen::MatrixXd& welded,
                                      const std::vector<int>& obj_to_sim) {
  Eigen::MatrixXd weights =
      Eigen::MatrixXd::Zero(welded.rows(), static_cast<Eigen::Index>(obj_to_sim.size()));
  for (Eigen::Index p = 0; p < weights.cols(); ++p) {
    const int s = obj_to_sim[static_cast<std::size_t>(p)];
    if (s >= 0)
      weights.col(p) = welded.col(s);
    else
      weights(0, p) = 1.0;
  }
  return weights;
}

/// The avatar's skin carried to the garment's document positions (#J×#P), by transfer
/// onto the written garment (welded, avatar units); unreferenced positions follow joint 0.
Eigen::MatrixXd garment_skin_weights(Run& run, const Inputs& in, const SkinBinding& skin,
                                     const MatrixX3d& garment_avatar_units) {
  const Scene& scene = in.scene;
  Eigen::MatrixXd body_weights(scene.avatar.sim_to_obj.size(), skin.weights.rows());
  for (std::size_t s = 0; s < scene.avatar.sim_to_obj.size(); ++s)
    body_weights.row(static_cast<Eigen::Index>(s)) =
        skin.weights.col(scene.avatar.sim_to_obj[s]).transpose();
  const TriangleMesh written{garment_avatar_units, scene.garment.mesh.faces};
  const SkinTransferResult transfer =
      transfer_skin_weights(scene.avatar.mesh, body_weights, written, run.options.skin_transfer);
  SkinTransferReport& report = run.report().skin;
  report = SkinTransferReport{true,
                              static_cast<int>(skin.joints.size()),
                              transfer.matched,
                              transfer.inpainted,
                              transfer.unreached,
                              transfer.seconds};
  run.progress.log("skin",
                   "{} of {} garment vertices took the avatar's weights directly, {} "
                   "inpainted ({:.2f} s)",
                   transfer.matched, written.vertices.rows(), transfer.inpainted, transfer.seconds);
  return on_document_positions(transfer.weights.transpose(), scene.garment.obj_to_sim);
}

/// Writes the garment (normalized #Vg×3) as a GLB in the avatar's frame and units, skinned
/// over the avatar's skeleton when the avatar has one.
void write_garment_glb(Run& run, const Inputs& in, const Eigen::Ref<const MatrixX3d>& garment) {
  const Normalization& n = in.normalized.normalization;
  const MatrixX3d welded = n.avatar_to_scene.invert_rows(garment);
  const MatrixX3d positions = export_positions(
      in.scene.garment_document, in.scene.garment, welded,
      [&](const Vector3d& p) { return n.avatar_to_scene.invert(n.garment_to_scene.apply(p)); });
  const GltfDocument* source = in.scene.garment_gltf ? &*in.scene.garment_gltf : nullptr;
  if (!source && !in.scene.garment_document.material_libraries.empty())
    run.warn("the OBJ garment's materials are not carried into the GLB (UVs are)");
  std::optional<SkinBinding> avatar_skin = avatar_skin_for_export(in.scene);
  const bool bound = !in.scene.avatar_skin && !in.scene.avatar_gltf && in.scene.target_skeleton &&
                     in.bound_skin_weights.size() != 0;
  if (bound)
    avatar_skin =
        skin_of_skeleton(*in.scene.target_skeleton,
                         on_document_positions(in.bound_skin_weights, in.scene.avatar.obj_to_sim));
  if (!avatar_skin) {
    run.warn(
        "the avatar has no skeleton (glTF skin or --target-skeleton): the GLB is written "
        "without a skin");
    write_glb(run.staged("garment.glb"), in.scene.garment_document, source, positions, nullptr);
    return;
  }
  if (!in.scene.avatar_skin && !bound)
    run.warn(
        "the avatar has no skin weights: the GLB's skin takes the avatar's vertices bound "
        "to their nearest bones");
  SkinBinding skin = *avatar_skin;
  skin.weights = garment_skin_weights(run, in, *avatar_skin, welded);
  write_glb(run.staged("garment.glb"), in.scene.garment_document, source, positions, &skin);
}

/// Open: the pierced faces the avatar still passes through or holds at the end leave the
/// garment to be written, so that what is written is free of the avatar.
void open_pierced_stage(Run& run, Inputs& in, const MatrixX3d& garment,
                        const DistanceField& distance_field) {
  if (in.pierced_faces.empty()) return;
  const std::vector<int> opened =
      faces_to_open(TriangleMesh{garment, in.normalized.garment.faces}, in.normalized.avatar,
                    distance_field, in.pierced_faces, run.parameters().solver.dhat);
  std::vector<int> document_faces;
  for (const int f : opened)
    document_faces.push_back(in.scene.garment.face_to_obj[static_cast<std::size_t>(f)]);
  std::sort(document_faces.begin(), document_faces.end());
  document_faces.erase(std::unique(document_faces.begin(), document_faces.end()),
                       document_faces.end());
  remove_document_faces(in.scene.garment_document,
                        in.scene.garment_gltf ? &*in.scene.garment_gltf : nullptr, document_faces);
  run.report().pierced.opened_document_faces = document_faces;
  run.progress.log("open",
                   "{} of the {} faces left out of the avatar contact still meet the "
                   "avatar: left out of the written garment",
                   document_faces.size(), in.pierced_faces.size());
  if (!document_faces.empty())
    run.warn(
        fmt::format("{} garment faces the body passes through (a cap or closed shell) are "
                    "opened: left out of the written file (report.json pierced_faces)",
                    document_faces.size()));
}

/// Write: the garment with its materials, in the avatar's frame and units.
void write_stage(Run& run, const Inputs& in, const MatrixX3d& garment) {
  const StageTimer timer;
  const std::string& format = run.options.format;
  const bool glb = format.empty() ? in.scene.garment_gltf.has_value() : format == "glb";
  if (glb) {
    run.result.garment_path = run.folder.final_path("garment.glb");
    write_garment_glb(run, in, garment);
    run.report().seconds.write = timer.seconds();
    return;
  }
  run.result.garment_path = run.folder.final_path("garment.obj");
  for (const auto& warning : copy_material_files(in.scene.garment_document, run.out.string(),
                                                 run.options.allow_external_assets))
    run.warn(warning);
  write_garment(run.staged("garment.obj"), in, garment);
  run.report().seconds.write = timer.seconds();
}

/// Certify: the exact check of the file as written, against the avatar file, with the
/// shape change beside it.
Certificate certify_stage(Run& run) {
  const StageTimer timer;
  const RetargetOptions& options = run.options;
  const std::string garment_file = run.staged(fs::path(run.result.garment_path).filename());
  const nlohmann::json extra = {
      {"inputs",
       {{"garment",
         {{"path", options.inputs.garment}, {"sha256", sha256_of_file(options.inputs.garment)}}},
        {"avatar",
         {{"path", options.inputs.avatar}, {"sha256", sha256_of_file(options.inputs.avatar)}}}}},
      {"output", {{"path", run.result.garment_path}, {"sha256", sha256_of_file(garment_file)}}},
      {"parameters", to_json(run.report())["parameters"]},
      {"shape", shape_report(run.report().shape, run.report().shape_thresholds)},
      {"quality", to_string(options.quality)}};
  ValidationOptions validation;
  validation.avatar_meshes = options.inputs.avatar_meshes;
  // Inherited pairs as faces of the written file, which lacks the opened faces.
  const std::vector<int>& opened = run.report().pierced.opened_document_faces;
  std::vector<FacePair> inherited;
  int face_count = 0;
  for (const FacePair& p : run.report().inherited.document_pairs)
    face_count = std::max({face_count, p.first + 1, p.second + 1});
  const std::vector<int> written_id = face_ids_after_removal(face_count, opened);
  for (const FacePair& p : run.report().inherited.document_pairs) {
    const int a = written_id[static_cast<std::size_t>(p.first)];
    const int b = written_id[static_cast<std::size_t>(p.second)];
    if (a >= 0 && b >= 0) inherited.push_back({a, b});
  }
  validation.inherited_self_pairs = {inherited};
  const Certificate certificate = certify_garment(garment_file, options.inputs.avatar, extra,
                                                  validation, run.result.garment_path);
  write_certificate(run.staged("certificate.json"), certificate);
  run.report().certified = certificate.certified();
  run.report().seconds.certify = timer.seconds();
  return certificate;
}

/// The shape limits that apply to a run. With skeletons the target's proportions set the
/// garment's size and place (goblin_puffer legitimately grows to 1.51 times its edge
/// lengths, 2.2 times its area, and its collar moves 0.28 of the diagonal, with its loops
/// where L_pos puts them along their bones): only the scale-free edge changes are checked,
/// and the loops' places along their bones are checked by the loop-offset warning.
ShapeThresholds applied_shape_thresholds(ShapeThresholds limits, bool has_skeletons) {
  if (!has_skeletons) return limits;
  constexpr double kOff = std::numeric_limits<double>::infinity();
  limits.min_scale = 0.0;
  limits.max_scale = kOff;
  limits.area_change = kOff;
  limits.loop_displacement = kOff;
  return limits;
}

/// Shape: the garment to be written against the input, both normalized; each exceeded
/// threshold a warning.
void shape_stage(Run& run, const Inputs& in, const MatrixX3d& garment) {
  RetargetReport& report = run.report();
  report.shape = measure_shape_change(in.normalized.garment, garment);
  report.shape_thresholds =
      applied_shape_thresholds(run.options.shape_thresholds, in.scene.source_skeleton.has_value());
  run.progress.log("shape",
                   "scale {:.3f}, scale-free edge change mean {:.3f} p95 {:.3f}, area "
                   "{:+.3f}, boundary loops moved up to {:.3f} of the diagonal",
                   report.shape.scale, report.shape.mean_edge_change, report.shape.p95_edge_change,
                   report.shape.area_change, report.shape.loop_displacement);
  for (const std::string& violation : shape_violations(report.shape, report.shape_thresholds))
    run.warn("shape changed beyond its threshold: " + violation +
             " (see --shape-check and the --max-* shape options)");
}

/// Ease: how much of its source ease the written garment kept.
void ease_measure_stage(Run& run, const Inputs& in, const std::vector<bool>& fit_faces,
                        const MatrixX3d& garment, const SourceEase& source) {
  EaseReport& ease = run.report().ease;
  ease.measure = measure_ease(in.normalized.garment, garment, in.normalized.avatar, source,
                              fit_faces, run.parameters().solver.dhat);
  const std::vector<int>& obj_to_sim = in.scene.garment.obj_to_sim;
  ease.document_ratio.assign(obj_to_sim.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t p = 0; p < obj_to_sim.size(); ++p)
    if (obj_to_sim[p] >= 0)
      ease.document_ratio[p] = ease.measure.ratio[static_cast<std::size_t>(obj_to_sim[p])];
  run.progress.log("ease",
                   "{} fit: ratio to the source ease median {:.3f}, mean error {:.3f}, "
                   "{:.1f}% of {} vertices within 25%",
                   to_string(ease.fit), ease.measure.median_ratio, ease.measure.mean_error,
                   100.0 * ease.measure.within_25_percent, ease.measure.vertices);
}

/// Measure: fit error of the written garment; the one-line summary.
std::string measure_stage(Run& run, const Inputs& in, const std::vector<bool>& fit_faces,
                          const MatrixX3d& garment, const Certificate& certificate,
                          double total_seconds) {
  RetargetReport& report = run.report();
  const Normalization& frames = in.normalized.normalization;
  const TriangleMesh& rest = in.normalized.garment;
  const TriangleMesh written{frames.avatar_to_scene.invert_rows(garment), rest.faces};
  report.fit_error = measure_fit_error(written, fit_faces, in.scene.avatar.mesh);
  const auto totals = certificate.validation.result.totals();
  // The solver sees only pairs within dhat; a garment that ended further away takes the
  // certificate's clearance, so the report never holds an infinity.
  if (!std::isfinite(report.min_distance))
    report.min_distance = totals.smallest_avatar_clearance * report.scene_scale;
  report.inherited.still_crossing = static_cast<int>(totals.inherited_self_intersections);
  const std::string inherited =
      report.inherited.pairs > 0
          ? fmt::format(" (and {} of the input's {} inherited)",
                        totals.inherited_self_intersections, report.inherited.pairs)
          : std::string();
  return fmt::format(
      "{}: {} garment-avatar and {} self intersections{}; min distance {:.3g} (avatar units); fit "
      "error mean {:.3g}, p95 {:.3g}; {:.1f} s",
      report.certified ? "certified" : "NOT certified", totals.garment_avatar_intersections,
      totals.garment_self_intersections, inherited, report.min_distance / report.scene_scale,
      report.fit_error.mean, report.fit_error.p95, total_seconds);
}

}  // namespace

RetargetResult run_retarget(const RetargetOptions& options) {
  const RunControl control(options.limits.timeout_seconds, options.limits.max_memory_mb);
  check_input_files(options.inputs, options.limits.max_input_mb);
  ResultFolder folder(options.out_dir, input_files(options.inputs), options.write_in_place);
  std::optional<tbb::global_control> thread_limit;
  if (options.threads > 0)
    thread_limit.emplace(tbb::global_control::max_allowed_parallelism,
                         static_cast<std::size_t>(options.threads));
  Run run(options, folder, control);
  RetargetReport& report = run.report();
  report.quality = options.quality;
  report.parameters = parameters_for_quality(options.quality);
  options.overrides.apply_to(report.parameters);
  const StageTimer total;
  // The report is the last file of the folder; a run that did not end certified keeps the
  // earlier result aside, so that it cannot be taken for this run's.
  const auto finish = [&](Outcome status, std::string message,
                          const std::function<void()>& before_commit = {}) {
    const bool certified =
        status == Outcome::kCertified || status == Outcome::kShapeChanged;
    run.result.status = status;
    run.result.message = std::move(message);
    if (!certified && folder.has_previous()) report.previous_result = folder.previous_path();
    report.seconds.total = total.seconds();
    report.peak_memory_mb = peak_memory_mb();
    write_report(run.staged("report.json"), report);
    if (before_commit) before_commit();
    folder.commit(!certified);
    return run.result;
  };

  Inputs in;
  in.scene = read_stage(run);
  in.normalized = normalize_stage(run, in.scene, in.inherited);
  // The source body gives the no-fit inference and the ease: read once.
  std::optional<TriangleMesh> source_body;
  if (!options.inputs.source_body.empty())
    source_body = read_source_body(options.inputs, in.scene, in.normalized);
  in.scene.no_fit = no_fit_for_run(in.scene, in.normalized, !options.inputs.no_fit.empty(),
                                   source_body ? &*source_body : nullptr, options.skirt,
                                   run.out.string(), options.inference, report.inferred);
  if (report.inferred.no_fit_inferred) {
    report.inferred.no_fit_path = folder.final_path("no-fit.txt");
    run.progress.log("no-fit", "inferred ({}): {} vertices, {} faces free, written to {}",
                     report.inferred.no_fit.method, report.inferred.no_fit.vertices.size(),
                     report.inferred.no_fit_faces, report.inferred.no_fit_path);
  }
  const SourceEase source_ease = ease_stage(run, in, source_body ? &*source_body : nullptr);
  control.check("read");

  const StageTimer shrink_timer;
  const SignedDistanceGrid grid = distance_grid_stage(run, in.normalized.avatar);
  const GridDistanceField distance_field(grid);
  Eigen::MatrixXd skin_weights;
  ShrinkResult shrunk;
  try {
    skin_weights = report.shrink_mode == ShrinkMode::kSkeleton
                       ? with_stop_hook(control,
                                        [&](const ProgressCallback& hook) {
                                          InferenceOptions inference = options.inference;
                                          inference.binding_options.progress = hook;
                                          Eigen::MatrixXd weights = skin_weights_for_shrink(
                                              in.scene, in.normalized, inference, report.inferred);
                                          report.inferred.binding_options.progress = nullptr;
                                          return weights;
                                        })
                       : in.scene.skin_weights;
    if (report.inferred.skin_weights_inferred) in.bound_skin_weights = skin_weights;
    if (report.inferred.skin_weights_inferred)
      run.progress.log("shrink", "skin weights inferred: {} binding in {:.2f} s",
                       report.inferred.binding_method, report.inferred.binding.seconds);
    shrunk = shrink_stage(run, in, skin_weights, grid);
  } catch (const NoValidShrinkError& e) {
    const Vector3d where =
        in.normalized.normalization.garment_to_scene.invert(e.conflict().position);
    report.seconds.shrink = shrink_timer.seconds();
    report.shrink_conflict =
        write_closest_shrink(run.out.string(), options.out_dir, in.scene, in.normalized, e);
    return finish(Outcome::kNoValidShrink,
                  fmt::format("no valid shrink: {} (near ({:.6g}, {:.6g}, {:.6g}) in the garment's "
                              "frame){}",
                              e.what(), where.x(), where.y(), where.z(),
                              pierced_cause(in, report.shrink_mode)));
  }
  record_shrink(run, shrunk, shrink_timer.seconds());

  SolverScene solver = solver_scene_stage(run, in, shrunk, distance_field);
  InflationResult inflation = inflate_stage(run, in, solver);
  if (!inflation.succeeded() && inflation.status != InflationStatus::kSolverFailure &&
      report.shrink_mode == ShrinkMode::kSkeleton) {
    const std::string no_thinner = inflate_from_thinner_shrink(
        run, in, skin_weights, grid, distance_field, shrunk, solver, inflation);
    // The shrunk avatar is what failed: one the garment can escape from does not exist.
    if (!no_thinner.empty())
      return finish(Outcome::kNoValidShrink,
                    fmt::format("the inflation from the skeleton shrink (pullback {:.3g}) "
                                "failed: {}; and no thinner shrink is free of the garment: {}",
                                shrunk.pullback, inflation.message, no_thinner));
  }
  if (!inflation.succeeded())
    return finish(Outcome::kSolverFailure,
                  "inflation failed: " + inflation.message +
                      "; allow more work with --max-al-rounds and --max-newton-iterations, or "
                      "widen the barrier with --dhat");
  if (report.ease.fit == FitMode::kEase) {
    EaseTargets targets =
        ease_targets(in.normalized.garment, inflation.garment, source_ease, report.ease.max_offset);
    solver.scene.fit_offsets = std::move(targets.offsets);
    report.ease.targets = std::move(targets);
    run.progress.log("fit",
                     "ease kept: local scale {:.3g} to {:.3g} (median {:.3g}), {} targets "
                     "capped",
                     report.ease.targets.min_scale, report.ease.targets.max_scale,
                     report.ease.targets.median_scale, report.ease.targets.capped);
  }
  const FitResult fit = fit_stage(run, solver, inflation.garment);
  if (fit.solve.status == SolverStatus::kNonFiniteEnergy || !std::isfinite(fit.solve.gradient_norm))
    return finish(Outcome::kSolverFailure, "fit failed: " + fit.solve.message);

  open_pierced_stage(run, in, fit.garment, distance_field);
  write_stage(run, in, fit.garment);
  shape_stage(run, in, fit.garment);
  if (report.ease.source_known)
    ease_measure_stage(run, in, solver.fit_faces, fit.garment, source_ease);
  const Certificate certificate = certify_stage(run);
  std::string summary =
      measure_stage(run, in, solver.fit_faces, fit.garment, certificate, total.seconds());
  run.progress.log("certify", "{}", summary);
  Outcome status =
      report.certified ? Outcome::kCertified : Outcome::kNotCertified;
  if (report.certified && !shape_violations(report.shape, report.shape_thresholds).empty()) {
    status = Outcome::kShapeChanged;
    summary += "; SHAPE CHANGED beyond its thresholds";
  }
  return finish(status, summary, [&]() {
    write_retarget_pages(run.out.string(), options.png, in.scene, in.normalized.normalization,
                         certificate, report);
  });
}

}  // namespace gr
