#include "tools/pipeline/stages/write_stage.hpp"

#include <algorithm>
#include <filesystem>
#include <optional>

#include <fmt/format.h>

#include "core/skeleton/skin_matching.hpp"
#include "tools/pipeline/pierced_faces.hpp"

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

/// Writes the garment (normalized #Vg×3) as a GLB in the avatar's frame and units, skinned
/// over the avatar's skeleton when the avatar has one.
void write_garment_glb(const WriteInput& input, const WriteOptions& options, WriteOutput& out,
                       Progress& progress) {
  const Scene& scene = input.scene;
  const Normalization& n = input.normalized.normalization;
  const std::string path = (fs::path(input.out_dir) / out.file_name).string();
  const MatrixX3d welded = n.avatar_to_scene.invert_rows(input.garment);
  const MatrixX3d positions = export_positions(
      scene.garment_document, scene.garment, welded,
      [&](const Vector3d& p) { return n.avatar_to_scene.invert(n.garment_to_scene.apply(p)); });
  const GltfDocument* source = scene.garment_gltf ? &*scene.garment_gltf : nullptr;
  if (!source && !scene.garment_document.material_libraries.empty())
    progress.warn("the OBJ garment's materials are not carried into the GLB (UVs are)");
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
    write_glb(path, scene.garment_document, source, positions, nullptr);
    return;
  }
  if (!scene.avatar_skin && !bound)
    progress.warn(
        "the avatar has no skin weights: the GLB's skin takes the avatar's vertices bound "
        "to their nearest bones");
  SkinBinding skin = *avatar_skin;
  skin.weights = garment_skin_weights(scene, *avatar_skin, welded, options, out.skin, progress);
  write_glb(path, scene.garment_document, source, positions, &skin);
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
  remove_document_faces(scene.garment_document, scene.garment_gltf ? &*scene.garment_gltf : nullptr,
                        document_faces);
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
  const Normalization& n = normalized.normalization;
  const MatrixX3d positions = export_positions(
      scene.garment_document, scene.garment, n.avatar_to_scene.invert_rows(garment),
      [&](const Vector3d& p) { return n.avatar_to_scene.invert(n.garment_to_scene.apply(p)); });
  write_obj(path, scene.garment_document, positions);
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
  if (glb) {
    out.file_name = "garment.glb";
    write_garment_glb(input, options, out, progress);
    out.seconds = timer.seconds();
    return out;
  }
  out.file_name = "garment.obj";
  for (const auto& warning : copy_material_files(input.scene.garment_document, input.out_dir,
                                                 options.allow_external_assets))
    progress.warn(warning);
  write_garment_obj((fs::path(input.out_dir) / out.file_name).string(), input.scene,
                    input.normalized, input.garment);
  out.seconds = timer.seconds();
  return out;
}

}  // namespace gr
