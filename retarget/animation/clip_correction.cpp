#include "retarget/animation/clip_correction.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>

#include "core/common/stopwatch.hpp"
#include "core/fit/garment_fit.hpp"
#include "core/inflation/avatar_inflation.hpp"
#include "core/mesh/simulation_mesh.hpp"
#include "garment/repairs/inherited_crossings.hpp"

namespace gr {

namespace {

/// Rings of neighbours around a crossing at rest whose self pairs are left out of contact,
/// as the prepare stage leaves them for the solve.
constexpr int kTangleRings = 2;

/// Tries of a frame, each in steps half as long as the one before.
constexpr int kAttempts = 3;

/// Passes the run's stop on to the solves without their per-step progress lines: a clip
/// runs a solve or two per frame.
class StopOnly final : public Interrupter {
 public:
  explicit StopOnly(Interrupter& outer) : outer_(outer) {}
  std::optional<Interrupted> interruption() const override { return outer_.interruption(); }

 private:
  Interrupter& outer_;
};

/// A uniform scale and shift that take the avatar at rest to the solver's units: its height
/// (largest extent) becomes 2, its box centred on the origin.
struct UnitFrame {
  double scale = 1.0;
  Eigen::RowVector3d centre = Eigen::RowVector3d::Zero();
  MatrixX3d to_solver(const MatrixX3d& p) const { return (p.rowwise() - centre) * scale; }
  MatrixX3d to_file(const MatrixX3d& p) const { return (p / scale).rowwise() + centre; }
};

UnitFrame unit_frame(const MatrixX3d& avatar) {
  const Eigen::RowVector3d low = avatar.colwise().minCoeff();
  const Eigen::RowVector3d high = avatar.colwise().maxCoeff();
  UnitFrame frame;
  frame.centre = 0.5 * (low + high);
  const double extent = (high - low).maxCoeff();
  frame.scale = extent > 0.0 ? 2.0 / extent : 1.0;
  return frame;
}

/// Every garment welded (seam copies one vertex, collapsed faces dropped, as the pipeline's
/// solver sees a garment) and stacked, faces renumbered: one mesh for the solver.
struct MergedGarments {
  std::vector<SimulationMesh> welded;  ///< per garment, over its document
  TriangleMesh rest;                   ///< file units
  std::vector<Eigen::Index> first;     ///< per garment, its first welded vertex
  std::vector<Eigen::Index> first_face;

  /// The garments' rows (file units) at the welded vertices.
  MatrixX3d stack(const std::vector<TriangleMesh>& garments) const {
    MatrixX3d all(rest.vertices.rows(), 3);
    for (std::size_t g = 0; g < garments.size(); ++g)
      for (std::size_t v = 0; v < welded[g].sim_to_obj.size(); ++v)
        all.row(first[g] + static_cast<Eigen::Index>(v)) =
            garments[g].vertices.row(welded[g].sim_to_obj[v]);
    return all;
  }
  /// Garment `g`'s rows from the welded positions; rows no face uses keep `skinned`'s.
  MatrixX3d rows_of(std::size_t g, const MatrixX3d& all, const MatrixX3d& skinned) const {
    MatrixX3d rows = skinned;
    for (Eigen::Index i = 0; i < rows.rows(); ++i)
      if (const int v = welded[g].obj_to_sim[static_cast<std::size_t>(i)]; v >= 0)
        rows.row(i) = all.row(first[g] + v);
    return rows;
  }
};

MergedGarments merge_garments(const AnimatedScene& scene) {
  MergedGarments merged;
  Eigen::Index rows = 0;
  Eigen::Index faces = 0;
  for (const AnimatedScene::Part& part : scene.garments) {
    merged.welded.push_back(make_simulation_mesh(part.asset.document));
    merged.first.push_back(rows);
    merged.first_face.push_back(faces);
    rows += merged.welded.back().mesh.vertices.rows();
    faces += merged.welded.back().mesh.faces.rows();
  }
  merged.rest.vertices.resize(rows, 3);
  merged.rest.faces.resize(faces, 3);
  for (std::size_t g = 0; g < scene.garments.size(); ++g) {
    const TriangleMesh& mesh = merged.welded[g].mesh;
    merged.rest.vertices.middleRows(merged.first[g], mesh.vertices.rows()) = mesh.vertices;
    merged.rest.faces.middleRows(merged.first_face[g], mesh.faces.rows()) =
        (mesh.faces.array() + static_cast<int>(merged.first[g])).matrix();
  }
  return merged;
}

/// The faces of the merged garments that cross at rest, within and between garments.
std::vector<FacePair> rest_pairs_merged(const AnimatedScene& scene, const MergedGarments& merged) {
  std::vector<std::vector<int>> welded_face(scene.garments.size());
  for (std::size_t g = 0; g < scene.garments.size(); ++g) {
    welded_face[g].assign(static_cast<std::size_t>(scene.garments[g].mesh.faces.rows()), -1);
    for (std::size_t f = 0; f < merged.welded[g].face_to_obj.size(); ++f)
      welded_face[g][static_cast<std::size_t>(merged.welded[g].face_to_obj[f])] =
          static_cast<int>(merged.first_face[g] + static_cast<Eigen::Index>(f));
  }
  std::vector<FacePair> pairs;
  const auto add = [&](std::size_t a, int fa, std::size_t b, int fb) {
    const int first = welded_face[a][static_cast<std::size_t>(fa)];
    const int second = welded_face[b][static_cast<std::size_t>(fb)];
    if (first >= 0 && second >= 0) pairs.push_back({first, second});
  };
  for (std::size_t g = 0; g < scene.garments.size(); ++g)
    for (const FacePair& p : scene.rest_self_pairs[g]) add(g, p.first, g, p.second);
  std::size_t pair = 0;
  for (std::size_t a = 0; a < scene.garments.size(); ++a)
    for (std::size_t b = a + 1; b < scene.garments.size(); ++b, ++pair)
      for (const FacePair& p : scene.rest_layer_pairs[pair]) add(a, p.first, b, p.second);
  return pairs;
}

/// A pose of the avatar and of every garment, each by its own skin.
struct ScenePose {
  SkeletonPose avatar;
  std::vector<SkeletonPose> garments;
};

ScenePose blend(const ScenePose& from, const ScenePose& to, double s) {
  ScenePose pose{blend_poses(from.avatar, to.avatar, s), {}};
  for (std::size_t g = 0; g < from.garments.size(); ++g)
    pose.garments.push_back(blend_poses(from.garments[g], to.garments[g], s));
  return pose;
}

/// The avatar and the garments as a pose puts them (file units), with the garments' joint
/// worlds.
struct PosedScene {
  TriangleMesh avatar;
  std::vector<TriangleMesh> garments;
  std::vector<std::vector<Eigen::Matrix4d>> garment_worlds;
};

/// The avatar and the garments skinned into `pose` (file units), each garment with its
/// bind-space morph offsets where `offsets` gives them.
PosedScene pose_scene(const AnimatedScene& scene, const ScenePose& pose,
                      const std::vector<MatrixX3d>* offsets = nullptr) {
  PosedScene posed;
  const SkinBinding& avatar_skin = *scene.avatar.asset.gltf.skin;
  posed.avatar = {
      pose_skinned_mesh(avatar_skin, scene.avatar.skinned, joint_worlds(avatar_skin, pose.avatar)),
      scene.avatar.mesh.faces};
  for (std::size_t g = 0; g < scene.garments.size(); ++g) {
    const AnimatedScene::Part& part = scene.garments[g];
    const SkinBinding& skin = *part.asset.gltf.skin;
    posed.garment_worlds.push_back(joint_worlds(skin, pose.garments[g]));
    posed.garments.push_back({pose_skinned_mesh(skin, part.skinned, posed.garment_worlds.back(),
                                                offsets ? &(*offsets)[g] : nullptr),
                              part.mesh.faces});
  }
  return posed;
}

/// The garments' rows of `garment_file` (file units, welded) as bind-space offsets from
/// their places in `posed`: what a morph target adds before skinning.
std::vector<MatrixX3d> bind_offsets(const AnimatedScene& scene, const MergedGarments& merged,
                                    const PosedScene& posed, const MatrixX3d& garment_file) {
  std::vector<MatrixX3d> offsets;
  for (std::size_t g = 0; g < scene.garments.size(); ++g) {
    const AnimatedScene::Part& part = scene.garments[g];
    const std::vector<Eigen::Matrix3d> linear =
        blend_linear_parts(*part.asset.gltf.skin, part.skinned, posed.garment_worlds[g]);
    const MatrixX3d& skinned = posed.garments[g].vertices;
    const MatrixX3d moved = merged.rows_of(g, garment_file, skinned) - skinned;
    MatrixX3d bind(moved.rows(), 3);
    for (Eigen::Index v = 0; v < moved.rows(); ++v)
      bind.row(v) = linear[static_cast<std::size_t>(v)]
                        .fullPivLu()
                        .solve(moved.row(v).transpose())
                        .transpose();
    offsets.push_back(std::move(bind));
  }
  return offsets;
}

}  // namespace

ClipCorrection correct_clip(const AnimatedScene& scene, const ChosenClip& chosen, double fps,
                            const ClipFindings& skinning_alone,
                            const RetargetParameters& parameters, double max_step,
                            Interrupter& interrupter) {
  const Stopwatch stopwatch;
  StopOnly quiet(interrupter);
  const AnimationClip& clip = chosen.clip;
  const SkinBinding& avatar_skin = *scene.avatar.asset.gltf.skin;
  const ClipBinding avatar_binding = bind_clip(avatar_skin, clip, chosen.translations);
  std::vector<ClipBinding> garment_bindings;
  for (const AnimatedScene::Part& part : scene.garments)
    garment_bindings.push_back(bind_clip(*part.asset.gltf.skin, clip, chosen.translations));

  const UnitFrame units = unit_frame(scene.avatar.mesh.vertices);
  RetargetParameters settle_parameters = parameters;
  settle_parameters.fit_max_iterations = parameters.settle_max_iterations;
  const MergedGarments merged = merge_garments(scene);
  const TriangleMesh rest{units.to_solver(merged.rest.vertices), merged.rest.faces};
  const std::vector<int> tangles =
      tangles_of(rest, rest_pairs_merged(scene, merged), kTangleRings).tangles;

  ScenePose previous{rest_pose(avatar_skin), {}};
  for (const AnimatedScene::Part& part : scene.garments)
    previous.garments.push_back(rest_pose(*part.asset.gltf.skin));
  MatrixX3d avatar_before = units.to_solver(scene.avatar.mesh.vertices);
  MatrixX3d garment_before = rest.vertices;  // the last pose's garment, solver units

  const std::vector<double> times = frame_times(clip, fps);
  if (skinning_alone.frames.size() != times.size())
    throw std::invalid_argument("the clip played by skinning alone has other frames");
  ClipCorrection result;
  result.target_of_frame.assign(times.size(), -1);
  for (std::size_t f = 0; f < times.size(); ++f) {
    ScenePose target{clip_pose(avatar_skin, clip, avatar_binding, times[f]), {}};
    for (std::size_t g = 0; g < scene.garments.size(); ++g)
      target.garments.push_back(
          clip_pose(*scene.garments[g].asset.gltf.skin, clip, garment_bindings[g], times[f]));
    const PosedScene at_target = pose_scene(scene, target);
    const MatrixX3d avatar_target = units.to_solver(at_target.avatar.vertices);
    // Skinning alone, then the last correction carried by the skin: the next frame starts
    // from whichever leaves this one free, with no solve.
    const bool free_alone = skinning_alone.frames[f].total() == 0;
    if (free_alone || !result.targets.empty()) {
      const PosedScene carried =
          free_alone ? PosedScene{} : pose_scene(scene, target, &result.targets.back());
      if (free_alone ||
          check_posed_frame(scene, carried.garments, at_target.avatar, times[f]).total() == 0) {
        if (!free_alone) {
          result.target_of_frame[f] = static_cast<int>(result.targets.size()) - 1;
          ++result.carried_frames;
        }
        garment_before = units.to_solver(merged.stack((free_alone ? at_target : carried).garments));
        avatar_before = avatar_target;
        previous = target;
        continue;
      }
    }
    const double reach = (avatar_target - avatar_before).rowwise().norm().maxCoeff();
    const int first_steps = std::max(1, static_cast<int>(std::ceil(reach / max_step)));
    const MatrixX3d garment_start = garment_before;
    const MatrixX3d avatar_start = avatar_before;
    // A step that cannot push the garment clear (a pinch between closing parts) is tried
    // again from the frame's start in steps half as long.
    for (int attempt = 0; attempt < kAttempts; ++attempt) {
      const int steps = first_steps << attempt;
      const bool last_attempt = attempt + 1 == kAttempts;
      garment_before = garment_start;
      avatar_before = avatar_start;
      bool stalled = false;
      for (int s = 1; s <= steps; ++s) {
        interrupter.check();
        std::optional<PosedScene> between;
        if (s < steps) between = pose_scene(scene, blend(previous, target, double(s) / steps));
        const PosedScene& posed = between ? *between : at_target;
        ++result.steps;
        const MatrixX3d avatar_now = units.to_solver(posed.avatar.vertices);
        const MatrixX3d skinned = merged.stack(posed.garments);
        if (s < steps &&
            check_posed_frame(scene, posed.garments, posed.avatar, times[f]).total() == 0) {
          garment_before = units.to_solver(skinned);
          avatar_before = avatar_now;
          continue;
        }
        ++result.solves;
        // The avatar moves from the last pose to this one, pushing the garment...
        GarmentScene moving;
        moving.garment = {garment_before, rest.faces};
        moving.avatar = {avatar_now, scene.avatar.mesh.faces};
        moving.shrunk_avatar = avatar_before;
        moving.garment_tangles = tangles;
        const Stopwatch push_time;
        const InflationResult pushed = inflate_avatar(moving, parameters, {}, quiet);
        result.push_seconds += push_time.seconds();
        result.push_iterations += pushed.newton_iterations;
        if (!pushed.succeeded() && !last_attempt) {
          stalled = true;
          break;
        }
        if (!pushed.succeeded()) {
          if (result.corrections_failed++ == 0)
            result.first_failure =
                fmt::format("frame {} step {} of {}: {} at t = {:.3g} ({})", f, s, steps,
                            to_string(pushed.status), pushed.t, pushed.message);
          // The garment where the push stopped is free of the avatar that far along its path:
          // the next step goes on from there, so a pinch costs the frames it lasts, and this
          // frame plays the cloth held at the pinch rather than skinned through the body.
          const bool usable = pushed.status != InflationStatus::kSolverFailure &&
                              pushed.garment.allFinite() && pushed.t >= 0.0 && pushed.t <= 1.0;
          if (usable) {
            garment_before = pushed.garment;
            avatar_before += pushed.t * (avatar_now - avatar_before);
            continue;
          }
          garment_before = units.to_solver(skinned);
        } else if (s < steps) {
          // A step on the way only has to keep the garment clear; the frame's pose settles it.
          garment_before = pushed.garment;
        } else {
          // ...then the garment settles toward its skinned place, keeping its rest shape.
          GarmentScene settling;
          settling.garment = rest;
          settling.avatar = std::move(moving.avatar);
          settling.shrunk_avatar = avatar_now;
          settling.garment_tangles = tangles;
          settling.tracked = units.to_solver(skinned);
          const Stopwatch settle_time;
          FitResult settled = fit_garment(settling, pushed.garment, settle_parameters, quiet);
          result.settle_seconds += settle_time.seconds();
          result.settle_iterations += settled.solve.iterations;
          garment_before = std::move(settled.garment);
        }
        avatar_before = avatar_now;
      }
      if (!stalled) break;
    }
    previous = target;
    ++result.solved_frames;
    result.target_of_frame[f] = static_cast<int>(result.targets.size());
    result.targets.push_back(bind_offsets(scene, merged, at_target, units.to_file(garment_before)));
  }
  result.seconds = stopwatch.seconds();
  return result;
}

}  // namespace gr
