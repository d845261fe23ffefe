#include "retarget/stages/write_stage.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <optional>
#include <set>

#include <fmt/format.h>

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

/// Writes the garment (normalized #Vg×3) as a GLB in the avatar's frame and units, skinned
/// over the avatar's skeleton when the avatar has one.
void write_garment_glb(const WriteInput& input, const WriteOptions& options, WriteOutput& out,
                       Progress& progress) {
  const Scene& scene = input.scene;
  const std::string path = (fs::path(input.out_dir) / out.file_name).string();
  const MatrixX3d positions = document_positions(scene, input.normalized, input.garment);
  const GltfDocument* source = scene.garment_gltf ? &*scene.garment_gltf : nullptr;
  if (!source && !scene.garment_document.material_libraries.empty())
    progress.warn("the OBJ garment's materials are not carried into the GLB (UVs are)");
  const std::optional<SkinBinding> skin = garment_skin(input, options, out, progress);
  write_glb(path, scene.garment_document, source, positions, skin ? &*skin : nullptr);
}

/// Writes each layer of an outfit: one GLB with a mesh each (or, split, a GLB each), or an
/// OBJ each.
void write_outfit(const WriteInput& input, const WriteOptions& options, bool glb, WriteOutput& out,
                  Progress& progress) {
  const Scene& scene = input.scene;
  const MatrixX3d positions = document_positions(scene, input.normalized, input.garment);
  std::optional<SkinBinding> skin;
  if (glb) skin = garment_skin(input, options, out, progress);
  std::vector<GlbMesh> meshes;
  std::vector<SkinBinding> skins(scene.layers.size());
  std::map<std::string, std::string> library_from;  // material file -> the garment it came from
  for (std::size_t k = 0; k < scene.layers.size(); ++k) {
    const GarmentLayer& layer = scene.layers[k];
    const MatrixX3d own = positions.middleRows(layer.first_position, layer.position_count);
    const std::string& stem = layer.file_stem;
    if (!glb) {
      out.garments.push_back({stem + ".obj", ""});
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
      if (!shared_library)
        for (const auto& warning :
             copy_material_files(layer.document, input.out_dir, options.allow_external_assets))
          progress.warn(warning);
      write_obj((fs::path(input.out_dir) / (stem + ".obj")).string(), layer.document, own);
      continue;
    }
    if (!layer.gltf && !layer.document.material_libraries.empty())
      progress.warn(
          fmt::format("{}: the OBJ garment's materials are not carried into the GLB "
                      "(UVs are)",
                      layer.path));
    if (skin) {
      skins[k] = *skin;
      skins[k].weights = skin->weights.middleCols(layer.first_position, layer.position_count);
    }
    GlbMesh mesh{layer.name, &layer.document, layer.gltf ? &*layer.gltf : nullptr, own,
                 skin ? &skins[k] : nullptr};
    if (options.split) {
      out.garments.push_back({stem + ".glb", ""});
      write_glb_meshes((fs::path(input.out_dir) / (stem + ".glb")).string(), {mesh});
    } else {
      out.garments.push_back({"outfit.glb", layer.name});
      meshes.push_back(std::move(mesh));
    }
  }
  if (!meshes.empty()) {
    out.file_name = "outfit.glb";
    write_glb_meshes((fs::path(input.out_dir) / out.file_name).string(), meshes);
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
  const bool glb =
      options.format.empty() ? input.scene.garment_gltf.has_value() : options.format == "glb";
  if (input.scene.layers.size() > 1) {
    write_outfit(input, options, glb, out, progress);
    out.seconds = timer.seconds();
    return out;
  }
  if (glb) {
    out.file_name = "garment.glb";
    out.garments = {{out.file_name, ""}};
    write_garment_glb(input, options, out, progress);
    out.seconds = timer.seconds();
    return out;
  }
  out.file_name = "garment.obj";
  out.garments = {{out.file_name, ""}};
  for (const auto& warning : copy_material_files(input.scene.garment_document, input.out_dir,
                                                 options.allow_external_assets))
    progress.warn(warning);
  write_garment_obj((fs::path(input.out_dir) / out.file_name).string(), input.scene,
                    input.normalized, input.garment);
  out.seconds = timer.seconds();
  return out;
}

}  // namespace gr
