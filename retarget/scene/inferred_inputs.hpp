#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "garment/fit/no_fit_inference.hpp"
#include "shrink/binding/voxel_binding.hpp"

namespace gr {

struct Scene;
struct ScenePaths;
struct NormalizedScene;

/// How avatar vertices find their bones when skeletons come without skin weights.
enum class BindingChoice {
  kGeodesic,  ///< bind_skeleton, geodesic through the interior (the default)
  kVisible,   ///< bind_skeleton, straight lines that stay inside
  kHeat,      ///< bind_skeleton, bone heat diffusion over the surface
  kNearest,   ///< no weights: the skeleton shrink takes each vertex's nearest bone
};

/// "geodesic", "visible", "heat" or "nearest".
const char* to_string(BindingChoice choice);
/// @throw InputError for any other name.
BindingChoice parse_binding_choice(const std::string& name);

/// What a run infers when the user does not give it, and how.
struct InferenceOptions {
  BindingChoice binding = BindingChoice::kGeodesic;
  BindingOptions binding_options;  ///< its method follows `binding`
  NoFitOptions no_fit;
};

/// What a run inferred, for report.json's `inferred`.
struct InferenceReport {
  /// Skin weights: whether they were computed, and the binding's numbers when they were.
  bool skin_weights_inferred = false;
  std::string binding_method;  ///< "geodesic", "visible", "heat" or "nearest"
  Binding binding;             ///< weights left out of the report
  BindingOptions binding_options;
  /// No-fit list: whether it was inferred, the rules and counts, where it was written.
  bool no_fit_inferred = false;
  NoFitInference no_fit;  ///< snug_offset in the garment file's units
  NoFitOptions no_fit_options;
  int no_fit_faces = 0;  ///< garment faces left free by the list used
  std::string no_fit_path;
  /// An outfit: the inferred list of each garment, its own vertex ids (`<stem>.no-fit.txt`,
  /// passed back with --no-fit once per garment), in the layers' order; no_fit_path empty.
  std::vector<std::string> no_fit_layer_paths;
};

nlohmann::json to_json(const InferenceReport& report);

/// The skin weights the skeleton shrink uses: the scene's when given, else (with skeletons
/// and a binding other than "nearest") weights bound on the normalized avatar and target
/// skeleton, recorded in `report`; else empty (nearest bone).
/// @return #J×#V (welded avatar vertices) or empty.
/// @throw InputError when the root joint is not a joint of the skeletons.
Eigen::MatrixXd skin_weights_for_shrink(const Scene& scene, const NormalizedScene& normalized,
                                        const InferenceOptions& options, InferenceReport& report);

/// The body the garment was made on (`paths.source_body`, OBJ or glTF in the garment's
/// frame, welded), placed in the normalized scene by the garment's normalization. A glTF
/// body is `paths.source_body_meshes` merged, by default every mesh its skin drives except
/// the garment's own mesh when the garment comes from the same file; a body cut away under
/// the clothes is valid.
/// @throw InputError when it cannot be read or has no (non-degenerate) triangle.
/// In an outfit, each garment's own body (GarmentPaths::source_body) is placed by its frame
/// (GarmentLayer::to_first_frame), and all are merged: one body for every layer.
/// When the garment was turned into the target's pose (Scene::garment_pose), a body of its
/// skin follows it; `followed_pose`, when given, says whether it did.
TriangleMesh read_source_body(const ScenePaths& paths, const Scene& scene,
                              const NormalizedScene& normalized, bool* followed_pose = nullptr);

/// Whether a source body was given, for the first garment or another of the outfit.
bool source_body_given(const ScenePaths& paths);
/// Whether a no-fit list was given, for any garment of the outfit (garments without one
/// then fit everywhere).
bool no_fit_given(const ScenePaths& paths);

/// The no-fit list a run uses, as welded garment vertex ids: the scene's when one was given
/// (its file named in ScenePaths::no_fit), else inferred (from `source_body` when not null,
/// see read_source_body) and written to `out_dir`/no-fit.txt as 0-based garment OBJ vertex
/// ids, recorded in `report`.
/// @throw InputError when the root joint is not a joint of the skeletons; OutputError when
///        the list cannot be written; InputError from find_leg_joints for a skirt (a layer's
///        GarmentLayer::skirt) whose skeleton has no legs.
std::vector<int> no_fit_for_run(const Scene& scene, const NormalizedScene& normalized,
                                bool list_given, const TriangleMesh* source_body,
                                const std::string& out_dir, const InferenceOptions& options,
                                InferenceReport& report);

}  // namespace gr
