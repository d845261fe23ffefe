#include "retarget/stages/shrink_stage.hpp"

#include <algorithm>
#include <iterator>
#include <set>

#include <fmt/format.h>

#include "garment/repairs/pierced_faces.hpp"

namespace gr {

namespace {

/// Pierced faces (ShrinkOptions::open_pierced_faces) grow by this many edge rings: the
/// shrunk avatar around a bone is a little thicker than the bone.
constexpr int kPiercedRings = 2;
/// Shrinks tried, each leaving out the faces the closest one met, before giving up; and the
/// largest share of the garment's faces left out (more means the garment is not around
/// the body the skeleton gives).
constexpr int kPiercedShrinks = 4;
constexpr double kMaxPiercedFraction = 0.25;

/// One shrink of the garment without `pierced`.
ShrinkResult shrink_once(const ShrinkInput& input, const ShrinkOptions& options,
                         const SignedDistanceGrid& grid, const std::vector<int>& pierced,
                         double pullback, Progress& progress) {
  return shrink_avatar(options.mode, scene_without_faces(input.normalized, pierced),
                       input.skin_weights, &grid, progress, pullback);
}

/// The shrink with pierced faces growing while none is free of the garment.
/// @throw NoValidShrinkError from the last shrink tried.
ShrinkResult shrink_leaving_out_pierced(const ShrinkInput& input, const ShrinkOptions& options,
                                        ShrinkOutput& out, Progress& progress) {
  const TriangleMesh& garment = input.normalized.garment;
  PiercedReport& report = out.pierced;
  std::vector<int>& pierced = out.pierced_faces;
  const auto max_faces =
      static_cast<std::size_t>(kMaxPiercedFraction * static_cast<double>(garment.faces.rows()));
  const auto leave_out = [&](const std::vector<int>& seeds) {
    std::vector<int> grown = faces_around(garment, seeds, kPiercedRings);
    std::vector<int> merged;
    std::set_union(pierced.begin(), pierced.end(), grown.begin(), grown.end(),
                   std::back_inserter(merged));
    if (merged.size() > max_faces) return false;
    pierced = std::move(merged);
    return true;
  };
  const PiercedByBones& by_bones = input.pierced_by_bones;
  if (!by_bones.pairs.empty()) {
    report.bones = by_bones.bones;
    if (leave_out(by_bones.faces))
      progress.log("shrink",
                   "{} garment faces pierced by {} source bones: {} left out of "
                   "the avatar contact",
                   by_bones.pairs.size(), by_bones.bones.size(), pierced.size());
  }
  for (int attempt = 1;; ++attempt) {
    report.shrinks = attempt;
    try {
      ShrinkResult shrunk =
          shrink_once(input, options, out.grid, pierced, options.pullback, progress);
      for (const int f : pierced)
        report.document_faces.push_back(
            input.scene.garment.face_to_obj[static_cast<std::size_t>(f)]);
      return shrunk;
    } catch (const NoValidShrinkError& e) {
      if (attempt == kPiercedShrinks ||
          e.closest().rows() != input.normalized.avatar.vertices.rows())
        throw;
      std::vector<int> met = faces_against_shrunk_avatar(
          TriangleMesh{e.closest(), input.normalized.avatar.faces}, garment);
      // With a skeleton the bones say where the body passes through the garment: only
      // the region around the faces they pierce grows. Without, the closest shrunk avatar
      // (the body's core) says it first.
      if (input.normalized.source_skeleton || !pierced.empty()) {
        std::vector<char> near(static_cast<std::size_t>(garment.vertices.rows()), 0);
        for (const int f : pierced)
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
      const std::size_t before = pierced.size();
      if (!leave_out(met) || pierced.size() == before) throw;
      progress.log("shrink",
                   "no shrink free of the garment: the closest meets {} faces; {} "
                   "left out of the avatar contact, shrinking again",
                   met.size(), pierced.size() - before);
    }
  }
}

/// The shrink's results in its report part, and its line in the progress.
void record_shrink(const ShrinkResult& shrunk, double seconds, ShrinkReport& report,
                   const Progress& progress) {
  report.depth = shrunk.depth;
  report.medial_vertices = shrunk.medial_vertices;
  report.full_depth_grid = shrunk.full_depth_grid;
  report.pullback = shrunk.pullback;
  progress.log("shrink", "{} shrink certified free of the garment in {:.2f} s",
               to_string(report.mode), seconds);
}

}  // namespace

NormalizedScene scene_without_faces(const NormalizedScene& normalized,
                                    const std::vector<int>& pierced_faces) {
  NormalizedScene scene = normalized;
  if (!pierced_faces.empty()) scene.garment = surface_without(scene.garment, pierced_faces);
  return scene;
}

std::string pierced_cause(const ShrinkInput& input, ShrinkMode mode) {
  const std::vector<FacePair>& pierced = input.pierced_by_bones.pairs;
  if (mode != ShrinkMode::kSkeleton || pierced.empty()) return "";
  return "; " + describe_pierced_faces(pierced, input.scene.garment.face_to_obj,
                                       *input.normalized.source_skeleton, input.scene.joint_names);
}

ShrinkOutput run_shrink(const ShrinkInput& input, const ShrinkOptions& options,
                        Progress& progress) {
  const StageTimer timer;
  ShrinkOutput out;
  out.report.mode = options.mode;
  const StageTimer grid_timer;
  out.grid = build_distance_grid(input.normalized.avatar, options.voxel_size, progress,
                                 options.distance_band);
  progress.log("shrink", "signed distance: {} voxels of {:.4g} in {:.2f} s",
               out.grid.active_voxel_count(), options.voxel_size, grid_timer.seconds());
  try {
    out.shrunk = options.open_pierced_faces
                     ? shrink_leaving_out_pierced(input, options, out, progress)
                     : shrink_once(input, options, out.grid, {}, options.pullback, progress);
  } catch (const NoValidShrinkError& e) {
    out.failure = e;
    out.seconds = timer.seconds();
    return out;
  }
  out.seconds = timer.seconds();
  record_shrink(out.shrunk, out.seconds, out.report, progress);
  return out;
}

std::string run_thinner_shrink(const ShrinkInput& input, const ShrinkOptions& options,
                               double pullback, ShrinkOutput& shrink, Progress& progress) {
  progress.log("inflate", "shrinking the avatar again with pullback {:.3g}", pullback);
  const StageTimer timer;
  ShrinkResult thinner;
  try {
    thinner = shrink_once(input, options, shrink.grid, shrink.pierced_faces, pullback, progress);
  } catch (const NoValidShrinkError& e) {
    return e.what();
  }
  shrink.shrunk = std::move(thinner);
  const double seconds = timer.seconds();
  shrink.seconds += seconds;
  record_shrink(shrink.shrunk, seconds, shrink.report, progress);
  shrink.report.thinned = true;
  return "";
}

}  // namespace gr
