#pragma once

#include "garment/repairs/inherited_crossings.hpp"
#include "retarget/report.hpp"
#include "retarget/run/progress.hpp"
#include "retarget/scene/normalization.hpp"

namespace gr {

struct NormalizeInput {
  const Scene& scene;
  const ScenePaths& paths;  ///< named in the progress line
};

struct NormalizeOptions {
  /// The thinnest barrier of the run (normalized units): coordinates are rounded to a
  /// lattice well below it (lattice_spacing).
  double thinnest_barrier = 0.0;
};

struct NormalizeOutput {
  NormalizedScene normalized;
  /// Where the garment crosses itself as given (normalized garment's faces).
  InheritedCrossings inherited;
  NormalizeReport report;
  /// The separation every CCD-bounded step must keep so that pairs apart on the rounded
  /// scene stay apart on the scene as given (normalized units).
  double ccd_min_separation = 0.0;
  double seconds = 0.0;
};

/// Normalize: the scene in normalized units, rounded to the lattice where that adds no
/// crossing of the garment with itself; the crossings it has as given are kept as
/// inherited, and pieces laid through other pieces attached to them. Logs the scene once
/// it is known good, with the read's warnings.
/// @throw InputError when garment and avatar are too far apart in size.
NormalizeOutput run_normalize(const NormalizeInput& input, const NormalizeOptions& options,
                              Progress& progress);

}  // namespace gr
