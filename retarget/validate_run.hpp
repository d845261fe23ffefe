#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "retarget/outcome.hpp"
#include "validate/measure/shape_change.hpp"
#include "validate/report/validation_report.hpp"

namespace gr {

/// Everything `garment-retarget validate` can be asked.
struct ValidateOptions {
  /// Garment OBJ or glTF files, each a layer (every pair of layers is checked too).
  std::vector<std::string> garments;
  /// glTF garments: the mesh per garment, or several (or "all") of a single garment file,
  /// each then a layer; empty: each file's default mesh.
  std::vector<std::string> garment_meshes;
  std::string avatar;                      ///< OBJ or glTF, in the garments' frame
  std::vector<std::string> avatar_meshes;  ///< glTF avatar: the meshes checked, merged
  std::string report;  ///< write the JSON validation report here (empty: not written)
  std::string marks;   ///< write an OBJ of the offending faces here (empty: not written)
  std::string html;    ///< write the HTML page here (empty: not written)
  /// Count garment vertices closer than this to the avatar (input units).
  std::optional<double> threshold;
  std::size_t max_listed = kDefaultListedIssues;  ///< entries per report list
  /// Per garment, its source garment (same vertices and faces) for the shape check; empty:
  /// no shape check.
  std::vector<std::string> sources;
  ShapeThresholds shape_thresholds;
  /// Clips to play the skinned garments and avatar through, every sampled frame checked
  /// exactly (see choose_clips for what a spec names); empty: the files' pose only.
  std::vector<std::string> animations;
  double fps = 30.0;  ///< frames sampled per second of a clip
};

/// How a validation ended.
struct ValidateResult {
  /// kCertified, kNotCertified (intersections found) or kShapeChanged (certified, but a
  /// garment's shape differs from its source beyond the thresholds).
  Outcome status = Outcome::kNotCertified;
  nlohmann::ordered_json report;      ///< the validation report, as options.report holds it
  std::string summary;                ///< one line for the user
  std::vector<std::string> warnings;  ///< one per shape threshold crossed
};

/// Checks the garments exactly against the avatar, themselves and each other, measures each
/// garment's shape against its source, and writes the report, marks and page asked for
/// (all or none: they are staged and moved into place together). Prints nothing.
/// @throw InputError for an unreadable input, a source that is not its garment's mesh, or
///        counts of sources or garment meshes that do not match the garments; OutputError
///        when an output cannot be written.
ValidateResult run_validate(const ValidateOptions& options);

}  // namespace gr
