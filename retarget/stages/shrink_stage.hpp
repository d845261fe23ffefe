#pragma once

#include <optional>
#include <string>
#include <vector>

#include "garment/repairs/pierced_faces.hpp"
#include "retarget/report.hpp"
#include "retarget/run/progress.hpp"
#include "retarget/scene/normalization.hpp"
#include "retarget/scene/shrink_avatar.hpp"
#include "shrink/level_set/signed_distance_grid.hpp"

namespace gr {

struct ShrinkInput {
  const Scene& scene;  ///< the garment's input face ids and the joint names, for the report
  const NormalizedScene& normalized;
  /// #J×#welded avatar vertices for the skeleton shrink, or empty (nearest bone).
  const Eigen::MatrixXd& skin_weights;
  /// Faces the source bones pierce (the prepare stage's), where the faces left out start.
  const PiercedByBones& pierced_by_bones;
};

struct ShrinkOptions {
  ShrinkMode mode = ShrinkMode::kLevelset;
  double voxel_size =
      PipelineParameters{}.voxel_size;  ///< signed-distance grid spacing (normalized units)
  /// How far outside the avatar the grid holds distances (the fit reads them there).
  double distance_band = kDistanceBand;
  double pullback = SkeletonShrinkOptions{}.pullback;  ///< skeleton: the first pullback tried
  /// Faces the avatar passes through as given leave the avatar contact (see run_shrink);
  /// false: such a garment has no valid shrink.
  bool open_pierced_faces = true;
};

struct ShrinkOutput {
  /// The avatar's signed distance near its surface: the shrink's, and the fit's to read.
  SignedDistanceGrid grid;
  ShrinkResult shrunk;  ///< valid unless `failure`
  /// Why no shrunk avatar is free of the garment, with the closest one tried.
  std::optional<NoValidShrinkError> failure;
  /// Garment faces left out of the avatar contact (the avatar passes through them as
  /// given), sorted rows of the normalized garment's faces.
  std::vector<int> pierced_faces;
  ShrinkReport report;
  PiercedReport pierced;  ///< the faces left out, for the pierced-faces report section
  double seconds = 0.0;
};

/// Shrink: the avatar's signed distance, then the avatar shrunk free of the garment. With
/// options.open_pierced_faces, faces the avatar passes through as given leave the avatar
/// contact: those the source bones pierce (without a skeleton: those the closest shrunk
/// avatar meets), then, while no shrunk avatar is free of the rest, those the closest one
/// meets next to them, each with a margin of edge rings; a few shrinks and a quarter of
/// the faces at most. A garment the bones pierce nowhere is never opened.
/// @throw Interrupted from progress (the run's limits).
ShrinkOutput run_shrink(const ShrinkInput& input, const ShrinkOptions& options, Progress& progress);

/// A second shrink of `shrink`'s scene with the same faces left out, thinner (`pullback`):
/// a thinner avatar leaves the garment more room between body parts. On success it
/// replaces shrink.shrunk, its report part (ShrinkReport::thinned) and adds its time.
/// @return empty on success, else why no thinner shrink is free of the garment (`shrink`
///         is then left as it was).
std::string run_thinner_shrink(const ShrinkInput& input, const ShrinkOptions& options,
                               double pullback, ShrinkOutput& shrink, Progress& progress);

/// The scene a shrunk avatar must be free of: the garment without `pierced_faces`.
NormalizedScene scene_without_faces(const NormalizedScene& normalized,
                                    const std::vector<int>& pierced_faces);

/// Why a skeleton shrink cannot be free of the garment when its bones pass through garment
/// faces (a closed shell, a capped leg; input.pierced_by_bones): "; " and the faces and
/// bones, else "".
std::string pierced_cause(const ShrinkInput& input, ShrinkMode mode);

}  // namespace gr
