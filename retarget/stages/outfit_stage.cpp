#include "retarget/stages/outfit_stage.hpp"

#include <algorithm>
#include <filesystem>
#include <numeric>

#include <fmt/format.h>

#include "core/common/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "core/io/formats/mesh_formats.hpp"
#include "garment/layers/layer_order.hpp"
#include "garment/repairs/pierced_faces.hpp"

namespace gr {

namespace fs = std::filesystem;

namespace {

/// Rays from a skeleton's bones when there is one, else from the body's faces, else none.
BodyRays body_rays(const std::optional<Skeleton>& skeleton, const TriangleMesh* body) {
  if (skeleton) return rays_from_skeleton(*skeleton);
  if (body && body->faces.rows() > 0) return rays_from_body_faces(*body);
  return {};
}

LayerOrderReport order_report(const LayerOrderMeasure& measure, const std::vector<int>& order) {
  const OutOfOrderRays out = rays_out_of_order(measure, order, 0);
  return {measure.rays_cast, out.rays_checked, out.out_of_order};
}

/// Writes the hidden faces, one 0-based avatar face id per line.
void write_hidden_faces(const std::string& path, const std::vector<int>& faces,
                        const std::string& avatar) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << "# avatar faces every garment of the outfit covers (0-based faces of " << avatar
        << " as read: a glTF avatar's meshes in order, their triangles in order)\n";
    for (const int f : faces) out << f << '\n';
  });
}

/// Writes the avatar without `faces` (sorted document faces) in its input's format,
/// skinned as it was where the format holds a skin; returns the file's name.
std::string write_avatar_without(const std::string& dir, const Scene& scene,
                                 const std::vector<int>& faces) {
  ObjDocument document = scene.avatar_document;
  std::optional<GltfDocument> gltf = scene.avatar_gltf;
  remove_document_faces(document, gltf ? &*gltf : nullptr, faces);
  const MeshFormat& format = mesh_format_for_path(scene.avatar_document.source_path);
  const SkinBinding* skin = format.skinned && scene.avatar_skin ? &*scene.avatar_skin : nullptr;
  const std::string name = "avatar" + format.written_extension();
  format.write((fs::path(dir) / name).string(),
               {GlbMesh{"", &document, gltf ? &*gltf : nullptr, document.positions, skin}},
               {false, false});
  return name;
}

}  // namespace

namespace {

/// The layer `name` names (GarmentLayer::name, its path as given or its file name).
/// @throw InputError from `option` when none does.
int find_layer(const Scene& scene, const std::string& name, const char* option) {
  for (std::size_t k = 0; k < scene.layers.size(); ++k) {
    const GarmentLayer& layer = scene.layers[k];
    if (name == layer.name || name == layer.path ||
        name == fs::path(layer.path).filename().string())
      return static_cast<int>(k);
  }
  throw InputError("", 0, fmt::format("{}: no garment named \"{}\"", option, name));
}

}  // namespace

void mark_skirts(Scene& scene, bool all, const std::vector<std::string>& names) {
  for (GarmentLayer& layer : scene.layers) layer.skirt = all;
  for (const std::string& name : names)
    scene.layers[static_cast<std::size_t>(find_layer(scene, name, "--skirt-layer"))].skirt = true;
}

std::vector<int> resolve_layer_order(const Scene& scene, const std::vector<std::string>& names) {
  if (names.empty()) return {};
  const auto layer_count = static_cast<int>(scene.layers.size());
  std::vector<int> order;
  for (const std::string& name : names) {
    const int found = find_layer(scene, name, "--layer-order");
    if (std::find(order.begin(), order.end(), found) != order.end())
      throw InputError("", 0, fmt::format("--layer-order: \"{}\" named twice", name));
    order.push_back(found);
  }
  if (static_cast<int>(order.size()) != layer_count)
    throw InputError("", 0,
                     fmt::format("--layer-order names {} of the {} garments: name each once",
                                 order.size(), layer_count));
  return order;
}

OutfitOutput run_outfit(const OutfitInput& input, const OutfitOptions& options,
                        Progress& progress) {
  const StageTimer timer;
  OutfitOutput out;
  OutfitReport& report = out.report;
  const Scene& scene = input.scene;
  const NormalizedScene& normalized = input.normalized;
  const auto layer_count = static_cast<int>(scene.layers.size());
  const std::vector<int> face_layer = layer_of_garment_faces(scene);

  // The order on the source: given, or measured where rays meet the layers.
  const LayeredOutfit source_outfit{normalized.garment, face_layer, layer_count};
  const LayerOrderMeasure on_source =
      measure_layer_order(source_outfit, input.source_body ? *input.source_body : TriangleMesh{},
                          body_rays(normalized.source_skeleton, input.source_body));
  std::vector<int> order = options.given_order;
  report.order_from = "given";
  if (order.empty()) {
    std::vector<int> listed(static_cast<std::size_t>(layer_count));
    std::iota(listed.begin(), listed.end(), 0);
    order = on_source.rays_meeting_several > 0 ? layer_order_from_votes(on_source.before, listed)
                                               : listed;
    report.order_from = on_source.rays_meeting_several > 0 ? "measured" : "given";
  }
  for (const int k : order) report.order.push_back(scene.layers[static_cast<std::size_t>(k)].name);
  report.source = order_report(on_source, order);

  // The order on the result, from the target's bones (else the avatar's faces).
  const LayeredOutfit result_outfit{
      {input.garment, normalized.garment.faces}, face_layer, layer_count};
  const LayerOrderMeasure on_result = measure_layer_order(
      result_outfit, normalized.avatar, body_rays(normalized.target_skeleton, &normalized.avatar));
  report.result = order_report(on_result, order);
  const auto share = [](const LayerOrderReport& r) {
    return r.rays_meeting_layers > 0 ? static_cast<double>(r.out_of_order) / r.rays_meeting_layers
                                     : 0.0;
  };
  std::string reordered;
  if (input.source_body && input.source_body->faces.rows() > 0) {
    const SourceOrderCheck check = rays_reordered_from_source(
        on_result, result_outfit.surface, normalized.garment, *input.source_body,
        options.order_tolerance, input.tangled_faces);
    report.reordered_from_source = check.reordered;
    report.rays_compared_with_source = check.rays_compared;
    report.order_kept = check.reordered == 0;
    reordered = fmt::format(
        "; of the {} with an order to keep, {} met the other way round than on the source",
        check.rays_compared, check.reordered);
  } else {
    report.order_kept =
        report.result.out_of_order == 0 ||
        (report.source.out_of_order > 0 && share(report.result) <= share(report.source));
  }
  progress.log("layers",
               "inside to outside ({}): {}; on the source {} of {} rays meeting two layers out of "
               "order, on the result {} of {}{}",
               report.order_from, fmt::join(report.order, ", "), report.source.out_of_order,
               report.source.rays_meeting_layers, report.result.out_of_order,
               report.result.rays_meeting_layers, reordered);
  if (!report.order_kept)
    progress.warn(
        report.reordered_from_source > 0
            ? fmt::format("the layer order is not kept: {} of {} rays from the body meet two "
                          "garments the other way round than on the source (report.json outfit)",
                          report.reordered_from_source, report.result.rays_meeting_layers)
            : fmt::format("the layer order is not kept: {} of {} rays from the body meet an "
                          "outer garment first (report.json outfit)",
                          report.result.out_of_order, report.result.rays_meeting_layers));

  const ValidationResult& checked = input.certificate.validation.result;
  for (const GarmentPairFindings& pair : checked.garment_pairs) {
    report.layer_intersections += pair.intersections.pairs.size();
    report.inherited_layer_intersections += pair.inherited_intersections;
  }

  // The body under the clothes.
  const HiddenFaces hidden = faces_hidden_by_outfit(
      normalized.avatar, {input.garment, normalized.garment.faces}, options.hidden);
  for (const int f : hidden.faces)
    out.hidden_document_faces.push_back(scene.avatar.face_to_obj[static_cast<std::size_t>(f)]);
  std::sort(out.hidden_document_faces.begin(), out.hidden_document_faces.end());
  out.hidden_document_faces.erase(
      std::unique(out.hidden_document_faces.begin(), out.hidden_document_faces.end()),
      out.hidden_document_faces.end());
  report.avatar_faces = static_cast<int>(scene.avatar_document.faces.size());
  report.hidden_faces = static_cast<int>(out.hidden_document_faces.size());
  report.kept_for_rays = hidden.kept_escaping;
  report.kept_for_margin = hidden.kept_near_opening;
  write_hidden_faces((fs::path(input.out_dir) / "hidden-avatar-faces.txt").string(),
                     out.hidden_document_faces, scene.avatar_document.source_path);
  report.hidden_faces_path = (fs::path(input.final_dir) / "hidden-avatar-faces.txt").string();
  if (options.write_avatar)
    report.avatar_path = (fs::path(input.final_dir) /
                          write_avatar_without(input.out_dir, scene, out.hidden_document_faces))
                             .string();
  progress.log(
      "hidden", "{} of {} avatar faces are under every garment{}", report.hidden_faces,
      report.avatar_faces,
      report.avatar_path.empty() ? "" : "; the avatar without them: " + report.avatar_path);
  report.seconds = timer.seconds();
  return out;
}

}  // namespace gr
