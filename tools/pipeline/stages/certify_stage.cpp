#include "tools/pipeline/stages/certify_stage.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include <fmt/format.h>

#include "tools/pipeline/metrics.hpp"
#include "tools/pipeline/pierced_faces.hpp"
#include "validate/report/file_digest.hpp"

namespace gr {

namespace {

/// The shape limits that apply to a run. With skeletons the target's proportions set the
/// garment's size and place (it may legitimately grow, and its collar move, with its loops
/// where L_pos puts them along their bones): only the scale-free edge changes are checked,
/// and the loops' places along their bones are checked by the fit's loop-offset warning.
ShapeThresholds applied_shape_thresholds(ShapeThresholds limits, bool has_skeletons) {
  if (!has_skeletons) return limits;
  constexpr double kOff = std::numeric_limits<double>::infinity();
  limits.min_scale = 0.0;
  limits.max_scale = kOff;
  limits.area_change = kOff;
  limits.loop_displacement = kOff;
  return limits;
}

/// The inherited pairs as faces of the written file, which lacks the opened faces.
std::vector<FacePair> inherited_pairs_as_written(const RetargetReport& report) {
  const std::vector<int>& opened = report.shrink.pierced.opened_document_faces;
  const std::vector<FacePair>& pairs = report.normalize.inherited.document_pairs;
  int face_count = 0;
  for (const FacePair& p : pairs) face_count = std::max({face_count, p.first + 1, p.second + 1});
  const std::vector<int> written_id = face_ids_after_removal(face_count, opened);
  std::vector<FacePair> inherited;
  for (const FacePair& p : pairs) {
    const int a = written_id[static_cast<std::size_t>(p.first)];
    const int b = written_id[static_cast<std::size_t>(p.second)];
    if (a >= 0 && b >= 0) inherited.push_back({a, b});
  }
  return inherited;
}

}  // namespace

CertifyOutput run_certify(const CertifyInput& input, const CertifyOptions& options,
                          Progress& progress) {
  CertifyOutput out;
  CertifyReport& report = out.report;
  report.shape = measure_shape_change(input.normalized.garment, input.garment);
  report.shape_thresholds =
      applied_shape_thresholds(options.shape_thresholds, input.scene.source_skeleton.has_value());
  progress.log("shape",
               "scale {:.3f}, scale-free edge change mean {:.3f} p95 {:.3f}, area "
               "{:+.3f}, boundary loops moved up to {:.3f} of the diagonal",
               report.shape.scale, report.shape.mean_edge_change, report.shape.p95_edge_change,
               report.shape.area_change, report.shape.loop_displacement);
  for (const std::string& violation : shape_violations(report.shape, report.shape_thresholds))
    progress.warn("shape changed beyond its threshold: " + violation +
                  " (see --shape-check and the --max-* shape options)");
  if (input.source_ease) {
    out.ease = measure_ease(input.normalized.garment, input.garment, input.normalized.avatar,
                            *input.source_ease, input.fit_faces, options.dhat);
    const std::vector<int>& obj_to_sim = input.scene.garment.obj_to_sim;
    out.ease_document_ratio.assign(obj_to_sim.size(), std::numeric_limits<double>::quiet_NaN());
    for (std::size_t p = 0; p < obj_to_sim.size(); ++p)
      if (obj_to_sim[p] >= 0)
        out.ease_document_ratio[p] = out.ease.ratio[static_cast<std::size_t>(obj_to_sim[p])];
    progress.log("ease",
                 "{} fit: ratio to the source ease median {:.3f}, mean error {:.3f}, "
                 "{:.1f}% of {} vertices within 25%",
                 to_string(input.report.ease.fit), out.ease.median_ratio, out.ease.mean_error,
                 100.0 * out.ease.within_25_percent, out.ease.vertices);
  }

  const StageTimer timer;
  const ScenePaths& paths = input.paths;
  const nlohmann::json extra = {
      {"inputs",
       {{"garment", {{"path", paths.garment}, {"sha256", sha256_of_file(paths.garment)}}},
        {"avatar", {{"path", paths.avatar}, {"sha256", sha256_of_file(paths.avatar)}}}}},
      {"output", {{"path", input.recorded_path}, {"sha256", sha256_of_file(input.written_file)}}},
      {"parameters", to_json(input.report)["parameters"]},
      {"shape", shape_report(report.shape, report.shape_thresholds)},
      {"quality", to_string(options.quality)}};
  ValidationOptions validation;
  validation.avatar_meshes = paths.avatar_meshes;
  validation.inherited_self_pairs = {inherited_pairs_as_written(input.report)};
  out.certificate =
      certify_garment(input.written_file, paths.avatar, extra, validation, input.recorded_path);
  report.certified = out.certificate.certified();
  out.seconds = timer.seconds();

  const Normalization& frames = input.normalized.normalization;
  const TriangleMesh written{frames.avatar_to_scene.invert_rows(input.garment),
                             input.normalized.garment.faces};
  report.fit_error = measure_fit_error(written, input.fit_faces, input.scene.avatar.mesh);
  out.inherited_still_crossing =
      static_cast<int>(out.certificate.validation.result.totals().inherited_self_intersections);
  return out;
}

std::string certify_summary(const Certificate& certificate, const RetargetReport& report,
                            double total_seconds) {
  const auto totals = certificate.validation.result.totals();
  const std::string inherited =
      report.normalize.inherited.pairs > 0
          ? fmt::format(" (and {} of the input's {} inherited)",
                        totals.inherited_self_intersections, report.normalize.inherited.pairs)
          : std::string();
  return fmt::format(
      "{}: {} garment-avatar and {} self intersections{}; min distance {:.3g} (avatar units); fit "
      "error mean {:.3g}, p95 {:.3g}; {:.1f} s",
      report.certified() ? "certified" : "NOT certified", totals.garment_avatar_intersections,
      totals.garment_self_intersections, inherited,
      report.fit.min_distance / report.normalize.scene_scale, report.certify.fit_error.mean,
      report.certify.fit_error.p95, total_seconds);
}

}  // namespace gr
