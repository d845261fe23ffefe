#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/solver/guide_path.hpp"
#include "garment/fit/ease.hpp"
#include "garment/fit/fit_error.hpp"
#include "garment/repairs/inherited_crossings.hpp"
#include "garment/repairs/non_manifold_edges.hpp"
#include "garment/repairs/pierced_faces.hpp"
#include "garment/repairs/untangle.hpp"
#include "retarget/parameters.hpp"
#include "retarget/scene/garment_pose.hpp"
#include "retarget/scene/inferred_inputs.hpp"
#include "retarget/scene/shrink_avatar.hpp"
#include "retarget/stages/animate_stage.hpp"
#include "validate/checks/mesh_intersections.hpp"
#include "validate/measure/shape_change.hpp"

namespace gr {

/// Wall time of each stage, seconds.
struct StageSeconds {
  double read = 0, normalize = 0, shrink = 0, proxy = 0, inflate = 0, fit = 0, write = 0,
         certify = 0, total = 0;
};

/// The skin written with a glTF garment (weights transferred from the avatar's skin).
struct SkinTransferReport {
  bool written = false;
  int joints = 0;
  int matched = 0;    ///< vertices that took the avatar's weights at their closest point
  int inpainted = 0;  ///< vertices filled in by the Laplacian solve
  int unreached = 0;  ///< of matched: in a part with no match, taken without the thresholds
  double seconds = 0.0;
};

/// How the fit treated the garment's ease, and how much of it the written garment kept.
struct EaseReport {
  FitMode fit = FitMode::kTight;
  bool source_known = false;   ///< a source body gave the source ease
  int filled_vertices = 0;     ///< over a cut in the source body (SourceEase::filled)
  double distance_band = 0.0;  ///< how far out the fit reads the avatar's distance (normalized)
  double max_offset = 0.0;     ///< the largest target the fit can hold (normalized)
  EaseTargets targets;         ///< the fit's local scale; offsets left empty in the report
  EaseMeasure measure;         ///< on the written garment; vertices 0 without a source body
  /// Per garment document position (OBJ `v` order), the measured ratio; NaN where none.
  std::vector<double> document_ratio;
};

/// The input repairs (the prepare stage), each a section of report.json of its own.
struct RepairsReport {
  NonManifoldReport non_manifold;  ///< `split_non_manifold_edges`
  UntangleReport untangle;         ///< `untangle`: the input's crossings pushed apart
  InheritedReport crossings;       ///< `inherited_crossings`, with the pieces attached
  PiercedReport pierced;  ///< `pierced_faces` (left out in the shrink, opened in the write)
};

/// Normalize: the scene in normalized units.
struct NormalizeReport {
  double scene_scale = 1.0;  ///< normalized units per avatar file unit
  double lattice = 0.0;      ///< normalized coordinates are multiples of this (0: exact)
  int garment_vertices = 0;
  int garment_faces = 0;
  int avatar_faces_total = 0;
  /// Share of the garment's area around bones the avatar has almost no surface around
  /// (measure_avatar_coverage), and those bones, most garment area first; skeletons only.
  double uncovered_share = 0.0;
  std::vector<std::string> uncovered_bones;
};

/// Shrink: the shrunk avatar the inflation starts from.
struct ShrinkReport {
  ShrinkMode mode = ShrinkMode::kLevelset;
  double depth = 0.0;            ///< levelset erosion d, normalized units (0 for skeleton)
  int medial_vertices = 0;       ///< vertices stopped in the medial region
  bool full_depth_grid = false;  ///< levelset: eroded deeper than the distance band
  double pullback = 0.0;         ///< skeleton: the pullback of the shrunk avatar inflated last
  /// skeleton: the inflation stalled from the first shrunk avatar and ran again from a
  /// thinner one
  bool thinned = false;
  /// After no valid shrink: the closest shrunk avatar written and the faces still crossing
  /// (write_closest_shrink); null otherwise.
  nlohmann::json conflict;
};

/// Inflate: the avatar grown back under barrier contact (Algorithm 1).
struct InflateReport {
  int al_rounds = 0;
  int resets = 0;
  int newton_iterations = 0;
  int factorizations = 0;  ///< Cholesky factorizations; the other steps reused a factor
  std::string status;
  /// Mean fraction of garment faces whose self-contact was left out as fold free per step.
  double fold_free = 0.0;
};

/// Coarse to fine: the decimated proxy solved first, and how far the garment followed it.
struct ProxyReport {
  bool used = false;
  std::string reason;  ///< why the garment was solved without one (empty when used)
  int faces = 0;       ///< the proxy's
  /// How much further out than the garment the proxy fits (CoarseProxy::clearance,
  /// normalized units).
  double clearance = 0.0;
  int inflate_newton_iterations = 0;
  int fit_newton_iterations = 0;
  double seconds = 0.0;
  /// How far the garment followed the proxy's paths (filled by the fine solves).
  GuideFollowed inflate_path, fit_path;
};

/// Fit: the garment settled onto the body, and what the solver modelled.
struct FitReport {
  int newton_iterations = 0;
  int factorizations = 0;  ///< Cholesky factorizations; the other steps reused a factor
  std::string status;
  std::map<std::string, double> energies;  ///< each term's value after the fit
  std::vector<std::string> terms;
  /// garment–avatar and garment–garment, normalized units (solver's view, pairs within
  /// dhat; else the certified garment–avatar clearance)
  double min_distance = 0.0;
  /// Per boundary loop held by L_pos: RMS offset from its place along its bone, in bone
  /// lengths, on the written garment.
  std::vector<double> loop_offsets;
  double surface_energy_per_area = 0.0;
  double fold_free = 0.0;  ///< as InflateReport::fold_free
  /// The fit was run again holding the pattern firmer (w_fit_stretch times
  /// kFirmerPatternFactor), its first result changing edges beyond the run's shape limits,
  /// and the second kept it better; the first's edge changes, scale free, when so
  /// (report.json fit.first_fit_edge_change).
  bool firmer_pattern = false;
  double first_mean_edge_change = 0.0;
  double first_p95_edge_change = 0.0;
  int fit_faces = 0;
  int avatar_faces_modelled = 0;
  bool self_contact = true;
  bool self_contact_everywhere = false;
};

/// Certify: the written garment checked exactly, and measured against the input.
struct CertifyReport {
  bool certified = false;
  FitError fit_error;  ///< avatar file units
  /// The written garment against the input garment, both in normalized units (so with
  /// skeletons the change of size the skeletons imply is already taken out).
  ShapeChange shape;
  ShapeThresholds shape_thresholds;  ///< as applied (see RetargetOptions::shape_thresholds)
};

/// Layer order on one side of the run, by rays from the body's bones (else its surface)
/// outward: along each, the first hit of each layer it meets.
struct LayerOrderReport {
  int rays = 0;
  int rays_meeting_layers = 0;  ///< rays that meet two or more layers
  int out_of_order = 0;         ///< of those, rays that meet an outer layer first
};

/// One garment of an outfit.
struct OutfitLayerReport {
  std::string name;  ///< GarmentLayer::name
  std::string path;
  std::string mesh;  ///< the glTF mesh read; empty for OBJ
  int faces = 0;
  std::string written;       ///< where it was written (final path)
  std::string written_mesh;  ///< its mesh in that file; empty: the whole file
  ShapeChange shape;         ///< its own change of shape (normalized units)
};

/// An outfit: its layers, their order, and the avatar faces they hide.
struct OutfitReport {
  std::vector<OutfitLayerReport> layers;  ///< in the order given
  std::vector<std::string> order;         ///< inside to outside, by name
  std::string order_from;                 ///< "given" (--layer-order) or "measured"
  LayerOrderReport source;                ///< the input on its source
  LayerOrderReport result;                ///< the written outfit on the avatar
  /// Rays of the result whose layers the same garment points met the other way round on the
  /// source (rays_reordered_from_source); -1 when there is no source body to compare with.
  int reordered_from_source = -1;
  int rays_compared_with_source = 0;  ///< rays of the result with an order to keep
  /// With a source body: no ray reordered from the source. Without: no ray meets an outer
  /// layer first on the result where none did on the source, else no more such rays, in
  /// proportion, than on the source.
  bool order_kept = false;
  std::size_t layer_intersections = 0;            ///< new garment–garment pairs (certificate)
  std::size_t inherited_layer_intersections = 0;  ///< inherited ones still crossing
  int avatar_faces = 0;
  int hidden_faces = 0;
  int kept_for_rays = 0;    ///< not hidden: a ray from the face escapes the outfit
  int kept_for_margin = 0;  ///< not hidden: within the margin of an opening
  std::string hidden_faces_path;
  std::string avatar_path;  ///< the avatar without its hidden faces (--write-avatar)
  double seconds = 0.0;
};

/// What a retarget run did and measured, one part per stage; written as report.json.
struct RetargetReport {
  Quality quality = Quality::kBalanced;
  PipelineParameters parameters;
  StageSeconds seconds;
  /// Peak memory estimated before the solve from the face counts (estimated_memory_mb).
  double estimated_memory_mb = 0.0;
  double peak_memory_mb = 0.0;
  /// Where the earlier result in the output folder was moved, when this run did not end
  /// certified; empty otherwise.
  std::string previous_result;

  NormalizeReport normalize;
  PoseReport pose;  ///< whether the garment was turned into the target's pose first
  RepairsReport repairs;
  InferenceReport inferred;  ///< the skin weights and no-fit list the run inferred, if any
  EaseReport ease;
  ShrinkReport shrink;
  ProxyReport proxy;
  InflateReport inflate;
  FitReport fit;
  SkinTransferReport skin;  ///< written with a GLB garment
  CertifyReport certify;
  std::optional<OutfitReport> outfit;      ///< set for several garments
  std::optional<AnimateOutput> animation;  ///< set when clips were played (--animation)

  std::vector<std::string> warnings;
  /// The written garment certified, and every sampled frame of the clips played.
  bool certified() const { return certify.certified && (!animation || animation->certified()); }
};

nlohmann::json to_json(const RetargetReport& report);
/// Each layer's shape as shape_report gives it: measured against `thresholds`.
nlohmann::json to_json(const OutfitReport& report, const ShapeThresholds& thresholds);
nlohmann::json to_json(const LayerOrderReport& report);

/// Peak resident memory of this process so far, MiB.
double peak_memory_mb();

}  // namespace gr
