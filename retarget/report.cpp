#include "retarget/report.hpp"

#include <cmath>

#include <sys/resource.h>

#include <fmt/format.h>

#include "retarget/scene/avatar_coverage.hpp"

namespace gr {

namespace {

nlohmann::json shape_json(const RetargetReport& r) {
  nlohmann::json shape = shape_report(r.certify.shape, r.certify.shape_thresholds);
  shape["surface_energy_per_area"] = r.fit.surface_energy_per_area;
  shape["units"] = "normalized scene units for both garments";
  return shape;
}

/// Every knob of parameter_table() as the run used it, with the lattice and the units.
nlohmann::json parameters_json(const RetargetReport& r) {
  nlohmann::json parameters = nlohmann::json::object();
  for (const ParameterRow& row : parameter_table()) {
    const double value = row.get(r.parameters);
    if (row.type == ParameterType::kCount)
      parameters[row.name] = static_cast<int>(value);
    else if (row.type == ParameterType::kSwitch)
      parameters[row.name] = value != 0.0;
    else
      parameters[row.name] = value;
  }
  parameters["lattice"] = r.normalize.lattice;
  parameters["units"] = "normalized scene units (avatar about 2 tall)";
  return parameters;
}

}  // namespace

nlohmann::json to_json(const LayerOrderReport& r) {
  return {{"rays", r.rays},
          {"rays_meeting_layers", r.rays_meeting_layers},
          {"out_of_order", r.out_of_order}};
}

nlohmann::json to_json(const OutfitReport& r, const ShapeThresholds& thresholds) {
  nlohmann::json layers = nlohmann::json::array();
  for (const OutfitLayerReport& l : r.layers)
    layers.push_back({{"name", l.name},
                      {"path", l.path},
                      {"mesh", l.mesh},
                      {"faces", l.faces},
                      {"written", l.written},
                      {"written_mesh", l.written_mesh},
                      {"shape", shape_report(l.shape, thresholds)}});
  return {{"layers", layers},
          {"order", r.order},
          {"order_from", r.order_from},
          {"order_on_source", to_json(r.source)},
          {"order_on_result", to_json(r.result)},
          {"rays_compared_with_source", r.rays_compared_with_source},
          {"reordered_from_source", r.reordered_from_source},
          {"order_kept", r.order_kept},
          {"layer_intersections", r.layer_intersections},
          {"inherited_layer_intersections", r.inherited_layer_intersections},
          {"hidden_avatar_faces",
           {{"avatar_faces", r.avatar_faces},
            {"hidden", r.hidden_faces},
            {"kept_for_rays", r.kept_for_rays},
            {"kept_for_margin", r.kept_for_margin},
            {"path", r.hidden_faces_path},
            {"avatar_written", r.avatar_path}}},
          {"seconds", r.seconds},
          {"meaning",
           "order: the garments from inside to outside; rays from the body's bones outward "
           "meet them in that order, out_of_order counts the rays that meet an outer layer "
           "first. reordered_from_source: rays of the result whose first hits lay the other "
           "way round from the source body, at the same garment points, by more than the "
           "barrier width (-1: no source body), of rays_compared_with_source (rays with two "
           "hits outside the input's tangles and over the body, not a cut); the order is kept "
           "when there is none. hidden: "
           "avatar faces every garment covers (no ray from the face's normal "
           "cone escapes the outfit, and no opening lies within the margin), listed in "
           "hidden-avatar-faces.txt"}};
}

namespace {

nlohmann::json guide_json(const GuideFollowed& followed) {
  return {{"points", followed.points},          {"reached", followed.points_reached},
          {"cut_by_ccd", followed.cut_motions}, {"held_back", followed.held_motions},
          {"recoveries", followed.recoveries},  {"recovery_steps", followed.recovery_steps},
          {"reached_end", followed.reached_end}};
}

nlohmann::json proxy_json(const ProxyReport& proxy) {
  if (!proxy.used) return {{"used", false}, {"reason", proxy.reason}};
  return {{"used", true},
          {"faces", proxy.faces},
          {"clearance", proxy.clearance},
          {"inflate_newton_iterations", proxy.inflate_newton_iterations},
          {"fit_newton_iterations", proxy.fit_newton_iterations},
          {"inflate_path", guide_json(proxy.inflate_path)},
          {"fit_path", guide_json(proxy.fit_path)}};
}

}  // namespace

nlohmann::json to_json(const RetargetReport& r) {
  using nlohmann::json;
  json report = {
      {"tool", {{"name", "garment-retarget"}, {"version", GR_VERSION}}},
      {"quality", to_string(r.quality)},
      {"parameters", parameters_json(r)},
      {"seconds",
       {{"read", r.seconds.read},
        {"normalize", r.seconds.normalize},
        {"shrink", r.seconds.shrink},
        {"proxy", r.seconds.proxy},
        {"inflate", r.seconds.inflate},
        {"fit", r.seconds.fit},
        {"write", r.seconds.write},
        {"certify", r.seconds.certify},
        {"total", r.seconds.total}}},
      {"shrink",
       {{"mode", to_string(r.shrink.mode)},
        {"depth", r.shrink.depth},
        {"medial_vertices", r.shrink.medial_vertices},
        {"full_depth_grid", r.shrink.full_depth_grid},
        {"pullback", r.shrink.pullback},
        {"thinned", r.shrink.thinned}}},
      {"proxy", proxy_json(r.proxy)},
      {"inflate",
       {{"al_rounds", r.inflate.al_rounds},
        {"resets", r.inflate.resets},
        {"newton_iterations", r.inflate.newton_iterations},
        {"factorizations", r.inflate.factorizations},
        {"status", r.inflate.status}}},
      {"fit",
       {{"newton_iterations", r.fit.newton_iterations},
        {"factorizations", r.fit.factorizations},
        {"status", r.fit.status},
        {"firmer_pattern", r.fit.firmer_pattern}}},
      {"energies", r.fit.energies},
      {"min_distance",
       {{"normalized", r.fit.min_distance},
        {"avatar_units", r.fit.min_distance / r.normalize.scene_scale}}},
      {"fit_error",
       {{"mean", r.certify.fit_error.mean},
        {"p95", r.certify.fit_error.p95},
        {"samples", r.certify.fit_error.samples},
        {"units", "avatar file units"}}},
      {"position",
       {{"loop_offsets", r.fit.loop_offsets},
        {"meaning",
         "per boundary loop held along its bone: RMS offset from its place on the "
         "bone, in lengths of the bone"}}},
      {"shape", shape_json(r)},
      {"modelled",
       {{"terms", r.fit.terms},
        {"self_contact", r.fit.self_contact},
        {"self_contact_where", !r.fit.self_contact ? "nowhere"
                               : r.fit.self_contact_everywhere
                                   ? "everywhere"
                                   : "where the garment can fold onto itself"},
        {"fold_free_face_fraction",
         {{"inflate", r.inflate.fold_free},
          {"fit", r.fit.fold_free},
          {"meaning",
           "mean share of garment faces per step in regions proven unable to fold "
           "onto themselves, whose self pairs were left out"}}},
        {"garment_vertices", r.normalize.garment_vertices},
        {"garment_faces", r.normalize.garment_faces},
        {"fit_faces", r.fit.fit_faces},
        {"avatar_faces_total", r.normalize.avatar_faces_total},
        {"avatar_faces_modelled", r.fit.avatar_faces_modelled}}},
      {"avatar_coverage",
       {{"uncovered_share", r.normalize.uncovered_share},
        {"uncovered_bones", r.normalize.uncovered_bones},
        {"meaning",
         fmt::format("share of the garment's area nearest bones (skeletons only) around which "
                     "the avatar has less than {:g}% of the garment's area there: a part the "
                     "avatar lacks",
                     100.0 * kMinAvatarToGarmentArea)}}},
      {"inferred", to_json(r.inferred)},
      {"peak_memory_mb", r.peak_memory_mb},
      {"estimated_memory_mb", r.estimated_memory_mb},
      {"certified", r.certified()},
      {"warnings", r.warnings},
  };
  report["pose"] = to_json(r.pose);
  if (r.animation) report["animation"] = to_json(*r.animation);
  report["skin"] = {{"written", r.skin.written},
                    {"joints", r.skin.joints},
                    {"matched_vertices", r.skin.matched},
                    {"inpainted_vertices", r.skin.inpainted},
                    {"unreached_vertices", r.skin.unreached},
                    {"seconds", r.skin.seconds}};
  const EaseReport& ease = r.ease;
  nlohmann::json per_vertex = nlohmann::json::array();
  for (const double ratio : ease.document_ratio)
    per_vertex.push_back(std::isfinite(ratio) ? nlohmann::json(ratio) : nlohmann::json(nullptr));
  report["ease"] = {
      {"fit", to_string(ease.fit)},
      {"source", ease.source_known ? "source body" : "none"},
      {"filled_vertices", ease.filled_vertices},
      {"distance_band", ease.distance_band},
      {"max_offset", ease.max_offset},
      {"scale",
       {{"min", ease.targets.min_scale},
        {"median", ease.targets.median_scale},
        {"max", ease.targets.max_scale}}},
      {"capped_vertices", ease.targets.capped},
      {"measured_vertices", ease.measure.vertices},
      {"garment_scale", ease.measure.scale},
      {"median_ratio", ease.measure.median_ratio},
      {"mean_error", ease.measure.mean_error},
      {"within_25_percent", ease.measure.within_25_percent},
      {"per_vertex_ratio", per_vertex},
      {"meaning",
       "ease: a fitted vertex's distance to the body. ratio: on the written garment, its "
       "distance to the avatar over the garment's median edge ratio, against its distance to "
       "the source body; per_vertex_ratio in OBJ vertex order, null where not measured"}};
  report["split_non_manifold_edges"] = to_json(r.repairs.non_manifold);
  if (r.repairs.untangle.pairs > 0) report["untangle"] = to_json(r.repairs.untangle);
  report["inherited_crossings"] = to_json(r.repairs.crossings);
  report["pierced_faces"] = to_json(r.repairs.pierced);
  if (r.fit.firmer_pattern)
    report["fit"]["first_fit_edge_change"] = {{"mean", r.fit.first_mean_edge_change},
                                              {"p95", r.fit.first_p95_edge_change}};
  if (r.outfit) report["outfit"] = to_json(*r.outfit, r.certify.shape_thresholds);
  if (!r.shrink.conflict.is_null()) report["shrink_conflict"] = r.shrink.conflict;
  if (!r.previous_result.empty()) report["previous_result"] = r.previous_result;
  return report;
}

double peak_memory_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is KiB on Linux
}

}  // namespace gr
