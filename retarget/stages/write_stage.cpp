#include "retarget/stages/write_stage.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <optional>
#include <set>

#include <fmt/format.h>

#include "core/io/formats/mesh_formats.hpp"
#include "core/skeleton/skin_matching.hpp"
#include "garment/repairs/pierced_faces.hpp"

namespace gr {

namespace fs = std::filesystem;

namespace {

/// Weights per welded vertex (#J×#welded) carried to a mesh's document positions (#J×#P)
/// through `obj_to_sim`; positions no face references follow joint 0.
Eigen::MatrixXd on_document_positions(const Eigen::MatrixXd& welded,
                                      const std::vector<int>& obj_to_sim) {
  Eigen::MatrixXd weights =
      Eigen::MatrixXd::Zero(welded.rows(), static_cast<Eigen::Index>(obj_to_sim.size()));
  for (Eigen::Index p = 0; p < weights.cols(); ++p) {
    const int s = obj_to_sim[static_cast<std::size_t>(p)];
    if (s >= 0)
      weights.col(p) = welded.col(s);
    else
      weights(0, p) = 1.0;
  }
  return weights;
}

/// The avatar's skin carried to the garment's document positions (#J×#P), by transfer
/// onto the written garment (welded, avatar units); unreferenced positions follow joint 0.
Eigen::MatrixXd garment_skin_weights(const Scene& scene, const SkinBinding& skin,
                                     const MatrixX3d& garment_avatar_units,
                                     const WriteOptions& options, SkinTransferReport& report,
                                     const Progress& progress) {
  Eigen::MatrixXd body_weights(scene.avatar.sim_to_obj.size(), skin.weights.rows());
  for (std::size_t s = 0; s < scene.avatar.sim_to_obj.size(); ++s)
    body_weights.row(static_cast<Eigen::Index>(s)) =
        skin.weights.col(scene.avatar.sim_to_obj[s]).transpose();
  const TriangleMesh written{garment_avatar_units, scene.garment.mesh.faces};
  const SkinTransferResult transfer =
      transfer_skin_weights(scene.avatar.mesh, body_weights, written, options.skin_transfer);
  report = SkinTransferReport{true,
                              static_cast<int>(skin.joints.size()),
                              transfer.matched,
                              transfer.inpainted,
                              transfer.unreached,
                              transfer.seconds};
  progress.log("skin",
               "{} of {} garment vertices took the avatar's weights directly, {} "
               "inpainted ({:.2f} s)",
               transfer.matched, written.vertices.rows(), transfer.inpainted, transfer.seconds);
  return on_document_positions(transfer.weights.transpose(), scene.garment.obj_to_sim);
}

/// The garment document's positions (#P×3) in the avatar's frame and units.
MatrixX3d document_positions(const Scene& scene, const NormalizedScene& normalized,
                             const Eigen::Ref<const MatrixX3d>& garment) {
  const Normalization& n = normalized.normalization;
  return export_positions(
      scene.garment_document, scene.garment, n.avatar_to_scene.invert_rows(garment),
      [&](const Vector3d& p) { return n.avatar_to_scene.invert(n.garment_to_scene.apply(p)); });
}

/// The skin of a written GLB over the garment document's positions (#J×#P weights): the
/// avatar's skeleton with its weights carried to the garment; unset (with a warning)
/// when the avatar has no skeleton.
std::optional<SkinBinding> garment_skin(const WriteInput& input, const WriteOptions& options,
                                        WriteOutput& out, Progress& progress) {
  const Scene& scene = input.scene;
  const MatrixX3d welded =
      input.normalized.normalization.avatar_to_scene.invert_rows(input.garment);
  std::optional<SkinBinding> avatar_skin = avatar_skin_for_export(scene);
  const bool bound = !scene.avatar_skin && !scene.avatar_gltf && scene.target_skeleton &&
                     input.bound_skin_weights.size() != 0;
  if (bound)
    avatar_skin =
        skin_of_skeleton(*scene.target_skeleton,
                         on_document_positions(input.bound_skin_weights, scene.avatar.obj_to_sim));
  if (!avatar_skin) {
    progress.warn(
        "the avatar has no skeleton (glTF skin or --target-skeleton): the GLB is written "
        "without a skin");
    return std::nullopt;
  }
  if (!scene.avatar_skin && !bound)
    progress.warn(
        "the avatar has no skin weights: the GLB's skin takes the avatar's vertices bound "
        "to their nearest bones");
  SkinBinding skin = *avatar_skin;
  skin.weights = garment_skin_weights(scene, *avatar_skin, welded, options, out.skin, progress);
  return skin;
}

/// Warns that an OBJ garment's material files stay behind in a format that keeps none.
void warn_materials_left(const MeshFormat& format, const ObjDocument& document,
                         const GltfDocument* source, const std::string& garment,
                         Progress& progress) {
  if (format.material_files || source || document.material_libraries.empty()) return;
  progress.warn(fmt::format("{}the OBJ garment's materials are not carried into the {} (UVs are)",
                            garment.empty() ? "" : garment + ": ", format.label));
}

/// Writes `meshes` into out_dir/file_name in `format`, with its warnings.
void write_meshes(const WriteInput& input, const WriteOptions& options, const MeshFormat& format,
                  const std::string& file_name, const std::vector<GlbMesh>& meshes,
                  bool copy_materials, Progress& progress) {
  const std::string path = (fs::path(input.out_dir) / file_name).string();
  for (const std::string& warning :
       format.write(path, meshes, {copy_materials, options.allow_external_assets}))
    progress.warn(warning);
}

/// Writes the garment (normalized #Vg×3) in the avatar's frame and units, skinned over the
/// avatar's skeleton when the format holds a skin and the avatar has one.
void write_garment(const WriteInput& input, const WriteOptions& options, const MeshFormat& format,
                   WriteOutput& out, Progress& progress) {
  const Scene& scene = input.scene;
  const MatrixX3d positions = document_positions(scene, input.normalized, input.garment);
  const GltfDocument* source = scene.garment_gltf ? &*scene.garment_gltf : nullptr;
  warn_materials_left(format, scene.garment_document, source, "", progress);
  std::optional<SkinBinding> skin;
  if (format.skinned) skin = garment_skin(input, options, out, progress);
  write_meshes(input, options, format, out.file_name,
               {GlbMesh{"", &scene.garment_document, source, positions, skin ? &*skin : nullptr}},
               true, progress);
}

/// Whether a material file this layer names came from another garment already: the first
/// one's is kept (with a warning), not copied again.
bool shares_material_library(const GarmentLayer& layer,
                             std::map<std::string, std::string>& library_from, Progress& progress) {
  bool shared_library = false;
  for (const std::string& library : layer.document.material_libraries) {
    const auto [it, added] = library_from.emplace(library, layer.path);
    if (!added && it->second != layer.path) {
      shared_library = true;
      progress.warn(
          fmt::format("{} and {} both name the material file {}: the first one's "
                      "is kept, and both garments use it",
                      it->second, layer.path, library));
    }
  }
  return shared_library;
}

/// Writes each layer of an outfit: one file with a mesh each when the format holds several
/// (unless split), else a file each.
void write_outfit(const WriteInput& input, const WriteOptions& options, const MeshFormat& format,
                  WriteOutput& out, Progress& progress) {
  const Scene& scene = input.scene;
  const MatrixX3d positions = document_positions(scene, input.normalized, input.garment);
  std::optional<SkinBinding> skin;
  if (format.skinned) skin = garment_skin(input, options, out, progress);
  const bool one_file = format.several_meshes && !options.split;
  const std::string outfit_file = "outfit" + format.written_extension();
  std::vector<GlbMesh> meshes;
  std::vector<SkinBinding> skins(scene.layers.size());
  std::map<std::string, std::string> library_from;  // material file -> the garment it came from
  for (std::size_t k = 0; k < scene.layers.size(); ++k) {
    const GarmentLayer& layer = scene.layers[k];
    const GltfDocument* source = layer.gltf ? &*layer.gltf : nullptr;
    const std::string file = layer.file_stem + format.written_extension();
    out.garments.push_back(one_file ? WrittenGarment{outfit_file, layer.name}
                                    : WrittenGarment{file, ""});
    const bool shared_library =
        format.material_files && shares_material_library(layer, library_from, progress);
    warn_materials_left(format, layer.document, source, layer.path, progress);
    if (skin) {
      skins[k] = *skin;
      skins[k].weights = skin->weights.middleCols(layer.first_position, layer.position_count);
    }
    GlbMesh mesh{layer.name, &layer.document, source,
                 positions.middleRows(layer.first_position, layer.position_count),
                 skin ? &skins[k] : nullptr};
    if (one_file)
      meshes.push_back(std::move(mesh));
    else
      write_meshes(input, options, format, file, {mesh}, !shared_library, progress);
  }
  if (!meshes.empty()) {
    out.file_name = outfit_file;
    write_meshes(input, options, format, out.file_name, meshes, true, progress);
  }
}

/// Removes document faces (sorted ids of the merged garment document) from an outfit's
/// layers and from the merged document, whose layer ranges follow.
void remove_layer_faces(Scene& scene, const std::vector<int>& document_faces) {
  remove_document_faces(scene.garment_document, nullptr, document_faces);
  int first_face = 0;
  for (GarmentLayer& layer : scene.layers) {
    std::vector<int> own;
    for (const int f : document_faces)
      if (f >= layer.first_face && f < layer.first_face + layer.face_count)
        own.push_back(f - layer.first_face);
    remove_document_faces(layer.document, layer.gltf ? &*layer.gltf : nullptr, own);
    layer.first_face = first_face;
    layer.face_count = static_cast<int>(layer.document.faces.size());
    first_face += layer.face_count;
  }
}

/// The pierced faces the avatar still passes through or holds at the end leave the
/// garment to be written.
std::vector<int> open_pierced_faces(const WriteInput& input, const WriteOptions& options,
                                    Progress& progress) {
  if (input.pierced_faces.empty()) return {};
  Scene& scene = input.scene;
  const std::vector<int> opened = faces_to_open(
      TriangleMesh{input.garment, input.normalized.garment.faces}, input.normalized.avatar,
      input.distance_field, input.pierced_faces, options.dhat);
  std::vector<int> document_faces;
  for (const int f : opened)
    document_faces.push_back(scene.garment.face_to_obj[static_cast<std::size_t>(f)]);
  std::sort(document_faces.begin(), document_faces.end());
  document_faces.erase(std::unique(document_faces.begin(), document_faces.end()),
                       document_faces.end());
  if (scene.layers.size() == 1) {
    remove_document_faces(scene.garment_document,
                          scene.garment_gltf ? &*scene.garment_gltf : nullptr, document_faces);
    scene.layers[0].document = scene.garment_document;
    scene.layers[0].gltf = scene.garment_gltf;
    scene.layers[0].face_count = static_cast<int>(scene.garment_document.faces.size());
  } else {
    remove_layer_faces(scene, document_faces);
  }
  progress.log("open",
               "{} of the {} faces left out of the avatar contact still meet the "
               "avatar: left out of the written garment",
               document_faces.size(), input.pierced_faces.size());
  if (!document_faces.empty())
    progress.warn(
        fmt::format("{} garment faces the body passes through (a cap or closed shell) are "
                    "opened: left out of the written file (report.json pierced_faces)",
                    document_faces.size()));
  return document_faces;
}

}  // namespace

void write_garment_obj(const std::string& path, const Scene& scene,
                       const NormalizedScene& normalized,
                       const Eigen::Ref<const MatrixX3d>& garment) {
  write_obj(path, scene.garment_document, document_positions(scene, normalized, garment));
}

void write_avatar_obj(const std::string& path, const Scene& scene,
                      const NormalizedScene& normalized,
                      const Eigen::Ref<const MatrixX3d>& avatar) {
  const Normalization& n = normalized.normalization;
  const MatrixX3d positions =
      export_positions(scene.avatar_document, scene.avatar, n.avatar_to_scene.invert_rows(avatar),
                       [](const Vector3d& p) { return p; });
  write_obj(path, scene.avatar_document, positions);
}

WriteOutput run_write(const WriteInput& input, const WriteOptions& options, Progress& progress) {
  WriteOutput out;
  out.opened_document_faces = open_pierced_faces(input, options, progress);
  const StageTimer timer;
  const MeshFormat& format =
      options.format ? *options.format : mesh_format_for_path(input.scene.layers.front().path);
  if (input.scene.layers.size() > 1) {
    write_outfit(input, options, format, out, progress);
  } else {
    out.file_name = "garment" + format.written_extension();
    out.garments = {{out.file_name, ""}};
    write_garment(input, options, format, out, progress);
  }
  out.seconds = timer.seconds();
  return out;
}

}  // namespace gr
