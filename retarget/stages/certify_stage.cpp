#include "retarget/stages/certify_stage.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include <fmt/format.h>

#include "garment/fit/fit_error.hpp"
#include "garment/repairs/pierced_faces.hpp"
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

/// The inherited pairs as faces of the written files, which lack the opened faces: each
/// layer's own pairs, and those between two layers.
void set_inherited_pairs_as_written(const RetargetReport& report, const Scene& scene,
                                    ValidationOptions& validation) {
  const std::vector<int>& opened = report.repairs.pierced.opened_document_faces;
  const std::vector<FacePair>& pairs = report.repairs.crossings.document_pairs;
  int face_count = 0;
  for (const FacePair& p : pairs) face_count = std::max({face_count, p.first + 1, p.second + 1});
  const std::vector<int> written_id = face_ids_after_removal(face_count, opened);
  // Written faces follow the layers in order (the opened faces taken out of each).
  const auto layer_of = [&](int face) {
    std::size_t k = 0;
    while (k + 1 < scene.layers.size() && face >= scene.layers[k + 1].first_face) ++k;
    return k;
  };
  validation.inherited_self_pairs.assign(scene.layers.size(), {});
  for (const FacePair& p : pairs) {
    const int a = written_id[static_cast<std::size_t>(p.first)];
    const int b = written_id[static_cast<std::size_t>(p.second)];
    if (a < 0 || b < 0) continue;
    const std::size_t la = layer_of(a);
    const std::size_t lb = layer_of(b);
    const int local_a = a - scene.layers[la].first_face;
    const int local_b = b - scene.layers[lb].first_face;
    if (la == lb) {
      validation.inherited_self_pairs[la].push_back(
          {std::min(local_a, local_b), std::max(local_a, local_b)});
      continue;
    }
    const bool in_order = la < lb;
    const auto first = static_cast<int>(in_order ? la : lb);
    const auto second = static_cast<int>(in_order ? lb : la);
    auto it = std::find_if(
        validation.inherited_layer_pairs.begin(), validation.inherited_layer_pairs.end(),
        [&](const InheritedLayerPairs& l) { return l.first == first && l.second == second; });
    if (it == validation.inherited_layer_pairs.end())
      it = validation.inherited_layer_pairs.insert(validation.inherited_layer_pairs.end(),
                                                   {first, second, {}});
    it->faces.push_back(in_order ? FacePair{local_a, local_b} : FacePair{local_b, local_a});
  }
}

/// The sub-mesh of `mesh` made of the faces of one layer, its vertices renumbered in order;
/// `positions` (#V×3, same rows as mesh.vertices) give its vertices' positions.
TriangleMesh layer_mesh(const TriangleMesh& mesh, const Eigen::Ref<const MatrixX3d>& positions,
                        const std::vector<int>& face_layer, int layer) {
  std::vector<int> vertex_id(static_cast<std::size_t>(mesh.vertices.rows()), -1);
  std::vector<int> faces;
  for (std::size_t f = 0; f < face_layer.size(); ++f)
    if (face_layer[f] == layer) faces.push_back(static_cast<int>(f));
  Eigen::MatrixX3i F(static_cast<Eigen::Index>(faces.size()), 3);
  int vertices = 0;
  for (Eigen::Index i = 0; i < F.rows(); ++i)
    for (int c = 0; c < 3; ++c) {
      int& id =
          vertex_id[static_cast<std::size_t>(mesh.faces(faces[static_cast<std::size_t>(i)], c))];
      if (id < 0) id = vertices++;
      F(i, c) = id;
    }
  MatrixX3d V(vertices, 3);
  for (std::size_t v = 0; v < vertex_id.size(); ++v)
    if (vertex_id[v] >= 0) V.row(vertex_id[v]) = positions.row(static_cast<Eigen::Index>(v));
  return {std::move(V), std::move(F)};
}

}  // namespace

CertifyOutput run_certify(const CertifyInput& input, const CertifyOptions& options,
                          Progress& progress) {
  CertifyOutput out;
  CertifyReport& report = out.report;
  // The change of shape counts the untangle's too: measured from the garment as given.
  const NormalizedScene& normalized = input.normalized;
  const TriangleMesh as_given{normalized.garment_as_given.rows() > 0 ? normalized.garment_as_given
                                                                     : normalized.garment.vertices,
                              normalized.garment.faces};
  report.shape = measure_shape_change(as_given, input.garment);
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
  const std::size_t layers = input.scene.layers.size();
  nlohmann::json extra = {
      {"inputs",
       {{"garment", {{"path", paths.garment}, {"sha256", sha256_of_file(paths.garment)}}},
        {"avatar", {{"path", paths.avatar}, {"sha256", sha256_of_file(paths.avatar)}}}}},
      {"output",
       {{"path", input.recorded_paths.front()},
        {"sha256", sha256_of_file(input.written_files.front())}}},
      {"parameters", to_json(input.report)["parameters"]},
      {"shape", shape_report(report.shape, report.shape_thresholds)},
      {"quality", to_string(options.quality)}};
  if (layers > 1) {
    const std::vector<int> face_layer = layer_of_garment_faces(input.scene);
    nlohmann::json inputs = nlohmann::json::array();
    nlohmann::json outputs = nlohmann::json::array();
    for (std::size_t k = 0; k < layers; ++k) {
      const GarmentLayer& layer = input.scene.layers[k];
      const TriangleMesh before =
          layer_mesh(as_given, as_given.vertices, face_layer, static_cast<int>(k));
      const TriangleMesh after =
          layer_mesh(input.normalized.garment, input.garment, face_layer, static_cast<int>(k));
      out.layer_shapes.push_back(measure_shape_change(before, after.vertices));
      // A layer destroyed under an outfit whose edges, counted together, changed little.
      for (const std::string& violation :
           shape_violations(out.layer_shapes.back(), report.shape_thresholds))
        progress.warn(
            fmt::format("{}: shape changed beyond its threshold: {}", layer.name, violation));
      inputs.push_back({{"name", layer.name},
                        {"path", layer.path},
                        {"mesh", layer.mesh},
                        {"sha256", sha256_of_file(layer.path)}});
      outputs.push_back(
          {{"name", layer.name},
           {"path", input.recorded_paths[k]},
           {"mesh", input.written_meshes[k]},
           {"sha256", sha256_of_file(input.written_files[k])},
           {"shape", shape_report(out.layer_shapes.back(), report.shape_thresholds)}});
    }
    extra["inputs"]["garments"] = inputs;
    extra["outputs"] = outputs;
  }
  ValidationOptions validation;
  validation.avatar_meshes = paths.avatar_meshes;
  validation.garment_meshes = input.written_meshes;
  set_inherited_pairs_as_written(input.report, input.scene, validation);
  out.certificate =
      certify_outfit(input.written_files, paths.avatar, extra, validation, input.recorded_paths);
  report.certified = out.certificate.certified();
  out.seconds = timer.seconds();

  const Normalization& frames = input.normalized.normalization;
  const TriangleMesh written{frames.avatar_to_scene.invert_rows(input.garment),
                             input.normalized.garment.faces};
  report.fit_error = measure_fit_error(written, input.fit_faces, input.scene.avatar.mesh);
  const ValidationTotals totals = out.certificate.validation.result.totals();
  out.inherited_still_crossing =
      static_cast<int>(totals.inherited_self_intersections + totals.inherited_layer_intersections);
  return out;
}

std::string certify_summary(const Certificate& certificate, const RetargetReport& report,
                            double total_seconds) {
  const auto totals = certificate.validation.result.totals();
  const std::string inherited =
      report.repairs.crossings.pairs > 0
          ? fmt::format(" (and {} of the input's {} inherited)",
                        totals.inherited_self_intersections, report.repairs.crossings.pairs)
          : std::string();
  const std::string layers =
      certificate.validation.garments.size() > 1
          ? fmt::format(", {} garment-garment ({} inherited)", totals.garment_garment_intersections,
                        totals.inherited_layer_intersections)
          : std::string();
  return fmt::format(
      "{}: {} garment-avatar and {} self intersections{}{}; min distance {:.3g} (avatar units); "
      "fit "
      "error mean {:.3g}, p95 {:.3g}; {:.1f} s",
      report.certified() ? "certified" : "NOT certified", totals.garment_avatar_intersections,
      totals.garment_self_intersections, inherited, layers,
      report.fit.min_distance / report.normalize.scene_scale, report.certify.fit_error.mean,
      report.certify.fit_error.p95, total_seconds);
}

}  // namespace gr
