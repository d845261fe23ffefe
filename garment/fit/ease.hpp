#pragma once

#include <string>
#include <vector>

#include "core/common/types.hpp"

namespace gr {

/// How the fit treats the distance between garment and body (its ease).
enum class FitMode {
  kEase,   ///< each fitted vertex is held at its source ease, scaled, from the avatar
  kTight,  ///< the paper's fit: every fitted face is pulled onto the avatar
};

/// "ease" or "tight".
const char* to_string(FitMode mode);
/// The mode named `name`. @throw InputError for any other name.
FitMode parse_fit_mode(const std::string& name);

/// The ease of a garment on its source body: per vertex, the distance to the body.
struct SourceEase {
  std::vector<double> distance;  ///< #Vg, the garment's units (normalized in the pipeline)
  /// Vertices whose nearest body face lies along a cut (an open edge of the body): the body
  /// was cut away under them, so their ease is their neighbours' (or 0 where no neighbour
  /// has one).
  int filled = 0;
};

/// Measures the garment's ease on `body` (both in one frame). A body cut away under the
/// clothes gives the ease where it exists (see SourceEase::filled).
/// @throw std::invalid_argument when the body has no face.
SourceEase measure_source_ease(const TriangleMesh& garment, const TriangleMesh& body);

/// The ease fit's targets: per garment vertex, the distance from the avatar it is held at.
struct EaseTargets {
  std::vector<double> offsets;  ///< #Vg, normalized units (GarmentScene::fit_offsets)
  /// The local scale applied to the source ease: per vertex, the median stretch of its
  /// edges from the input garment to the inflated one, averaged over its neighbourhood.
  double min_scale = 1.0, median_scale = 1.0, max_scale = 1.0;
  int capped = 0;  ///< vertices whose target was cut to max_offset
};

/// Targets for the fit from the source ease and the scale the retarget applies there,
/// measured on the inflated garment (#Vg×3, rows of `rest`): the local median edge stretch,
/// smoothed over two rings and kept within [1/2, 2] of the global median. A target is at
/// most `max_offset` (the reach of the avatar's distance field).
EaseTargets ease_targets(const TriangleMesh& rest, const Eigen::Ref<const MatrixX3d>& inflated,
                         const SourceEase& source, double max_offset);

/// The ease a written garment kept: per vertex, its distance to the avatar divided by the
/// garment's overall scale (the median edge ratio from the input), against its source
/// ease. Measured at vertices of fitted faces whose source ease is at least `min_ease`.
struct EaseMeasure {
  std::vector<double> ratio;  ///< #Vg: output ease / source ease; NaN where not measured
  int vertices = 0;           ///< vertices measured
  double scale = 1.0;         ///< the garment's median edge ratio
  double median_ratio = 0.0;
  double mean_error = 0.0;         ///< mean |ratio - 1|
  double within_25_percent = 0.0;  ///< share of measured vertices with |ratio - 1| <= 0.25
};

/// @param rest, written the garment before and after (normalized, same rows).
/// @param avatar the avatar in the same frame.
/// @param fit_faces per face of rest, whether it fits (no-fit faces are not measured).
EaseMeasure measure_ease(const TriangleMesh& rest, const Eigen::Ref<const MatrixX3d>& written,
                         const TriangleMesh& avatar, const SourceEase& source,
                         const std::vector<bool>& fit_faces, double min_ease);

}  // namespace gr
