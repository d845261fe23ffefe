#pragma once

#include <vector>

#include "garment/repairs/inherited_crossings.hpp"
#include "garment/repairs/pierced_faces.hpp"
#include "retarget/report.hpp"
#include "retarget/run/progress.hpp"
#include "retarget/scene/normalization.hpp"

namespace gr {

struct PrepareInput {
  Scene& scene;             ///< as read; the repairs of its garment surface change it
  const ScenePaths& paths;  ///< named in the progress line
};

struct PrepareOptions {
  /// The thinnest barrier of the run (normalized units): coordinates are rounded to a
  /// lattice well below it (lattice_spacing).
  double thinnest_barrier = 0.0;
  /// The layers of an outfit inside to outside (resolve_layer_order); empty: measured on
  /// the source, for the untangle to know which way a crossing between layers goes.
  std::vector<int> layer_order{};
};

struct PrepareOutput {
  NormalizedScene normalized;
  /// Where the garment crosses itself as given (normalized garment's faces).
  InheritedCrossings inherited;
  /// Faces the source bones pierce (normalized garment's faces); empty without skeletons.
  PiercedByBones pierced;
  NormalizeReport report;
  RepairsReport repairs;
  /// The separation every CCD-bounded step must keep so that pairs apart on the rounded
  /// scene stay apart on the scene as given (normalized units).
  double ccd_min_separation = 0.0;
  double seconds = 0.0;
};

/// Prepare: the input repairs and the normalization. Each repair is a unit of
/// garment/repairs with its own section of the report, listed once in prepare_stage.cpp:
/// edges of more than two faces split, then the scene in normalized units (rounded to the
/// lattice where that adds no crossing of the garment with itself), the crossings it has as
/// given kept as inherited with the pieces laid through other pieces attached to them, and
/// the faces the source bones pierce found for the shrink to leave out. Logs the scene once
/// it is known good, with the read's warnings.
/// @throw InputError when garment and avatar are too far apart in size.
PrepareOutput run_prepare(const PrepareInput& input, const PrepareOptions& options,
                          Progress& progress);

}  // namespace gr
