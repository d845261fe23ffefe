#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/io/formats/mesh_format.hpp"
#include "core/skinning/skin_weight_transfer.hpp"
#include "garment/fit/ease.hpp"
#include "retarget/outcome.hpp"
#include "retarget/parameters.hpp"
#include "retarget/report.hpp"
#include "retarget/run/run_control.hpp"
#include "retarget/scene/inferred_inputs.hpp"
#include "retarget/scene/scene.hpp"
#include "retarget/scene/shrink_avatar.hpp"

namespace gr {

/// Everything `garment-retarget retarget` can be asked.
struct RetargetOptions {
  ScenePaths inputs;
  std::string out_dir;
  bool skirt = false;  ///< every garment is a skirt (GarmentLayer::skirt)
  /// An outfit: the garments that are skirts, by name (GarmentLayer::name) or file.
  std::vector<std::string> skirt_layers;
  std::optional<ShrinkMode>
      shrink_mode;  ///< unset: skeleton when skeletons are given, else levelset
  Quality quality = Quality::kBalanced;
  /// unset: ease when the source ease is known (inputs.source_body), else tight
  std::optional<FitMode> fit_mode;
  ParameterOverrides overrides;  ///< individual knobs over the preset
  /// Skin weights and no-fit list inferred when inputs.skin_weights / inputs.no_fit are empty.
  InferenceOptions inference;
  /// Limits on the written garment's change of shape from the input (report.json `shape`);
  /// beyond them the run ends with Outcome::kShapeChanged.
  ShapeThresholds shape_thresholds;
  int threads = 0;      ///< 0: all cores
  bool frames = false;  ///< write intermediate garment/avatar OBJs
  bool png = false;     ///< also write front.png and side.png beside report.html
  bool quiet = false;
  /// Written garment format (mesh_formats()); null: the first garment's input format.
  const MeshFormat* format = nullptr;
  /// An outfit written as GLB: a file per garment instead of one file with a mesh each.
  bool split = false;
  /// An outfit: also write the avatar without the faces every garment hides
  /// (hidden-avatar-faces.txt), skinned as it was.
  bool write_avatar = false;
  /// An outfit: the garments from inside to outside, by name (GarmentLayer::name) or file;
  /// empty: measured on the source.
  std::vector<std::string> layer_order;
  /// When a written GLB's skin takes the avatar's weights directly (see
  /// transfer_skin_weights).
  SkinTransferOptions skin_transfer;
  /// Input sizes, faces, memory and time the run may take.
  RunLimits limits;
  /// Copy material files and textures that symbolic links lead to outside the OBJ's folder.
  bool allow_external_assets = false;
  /// Write into out_dir directly instead of swapping a complete result folder into place
  /// (ResultFolder): for callers that give each run a private folder of their own.
  bool write_in_place = false;
  /// Garment faces the avatar passes through as given (a cap a bone pierces, a hand laid
  /// through a skirt), so that no shrunk avatar is free of them: open (left out of the
  /// avatar contact, and out of the written garment where the avatar still passes through
  /// them at the end) or refuse (no valid shrink, naming the faces and bones).
  bool open_pierced_faces = true;
  /// Clips to play the written garment through (see ValidateOptions::animations): every
  /// sampled frame where skinning lets it cross is corrected, the corrections written as
  /// morph targets, and every frame certified. Needs a skinned GLB avatar and output.
  std::vector<std::string> animations;
  double fps = 30.0;  ///< frames sampled per second of a clip
  /// The pose the solve starts the garment in: the target's (turned by its own skin, where
  /// garment and avatar both have a glTF skin) or the one its file shows.
  PoseMode pose = PoseMode::kTarget;
  SkinningMethod pose_skinning = SkinningMethod::kLinearBlend;
  bool write_posed = false;  ///< also write the garment as posed (posed-garment.obj)
};

/// How a retarget run ended: kCertified, kNotCertified, kNoValidShrink, kSolverFailure or
/// kShapeChanged (certified and written, but the garment's shape changed beyond
/// RetargetOptions::shape_thresholds; each violation is a warning in the report).
struct RetargetResult {
  Outcome status = Outcome::kSolverFailure;
  std::string garment_path;  ///< the written garment, when one was written
  std::string report_path;
  std::string message;  ///< one line for the user
  RetargetReport report;
};

/// Runs the pipeline: read, normalize, shrink, inflate, fit, export, certify. Every file is
/// written into a staging folder that replaces out_dir in one step at the end (see
/// ResultFolder): a run that returns leaves its whole result there, the earlier result
/// removed when it is certified (kCertified, kShapeChanged), else kept at
/// out_dir.previous; a run that throws leaves out_dir as it was.
/// @throw InputError for bad inputs or inputs beyond options.limits, OutputError when
///        out_dir cannot be written or another run holds it, Interrupted at the deadline,
///        the memory limit or a stop request.
RetargetResult run_retarget(const RetargetOptions& options);

}  // namespace gr
