#pragma once

#include <string>
#include <vector>

#include "core/energies/distance_field.hpp"
#include "core/io/formats/mesh_format.hpp"
#include "core/skinning/skin_weight_transfer.hpp"
#include "retarget/report.hpp"
#include "retarget/run/progress.hpp"
#include "retarget/scene/normalization.hpp"

namespace gr {

struct WriteInput {
  /// The scene as read; its garment document loses the opened faces.
  Scene& scene;
  const NormalizedScene& normalized;
  const MatrixX3d& garment;               ///< the fitted garment (normalized #Vg×3)
  const std::vector<int>& pierced_faces;  ///< left out of the avatar contact (ShrinkOutput)
  const DistanceField& distance_field;    ///< the avatar's, normalized
  /// Skin weights bound to the target skeleton when none were given (#J×#welded avatar
  /// vertices), for a written GLB's skin; empty otherwise.
  const Eigen::MatrixXd& bound_skin_weights;
  std::string out_dir;  ///< where the files are written (the staging folder)
};

struct WriteOptions {
  /// The written garment's format (mesh_formats()); null: the first garment's input format.
  const MeshFormat* format = nullptr;
  /// An outfit written as GLB: a file per garment instead of one with a mesh each.
  bool split = false;
  bool allow_external_assets = false;
  SkinTransferOptions skin_transfer;
  double dhat = RetargetParameters{}
                    .dhat;  ///< pierced faces this close to the avatar are opened (normalized)
};

/// One written garment file, and the mesh in it that is the garment (glTF; empty: the
/// whole file).
struct WrittenGarment {
  std::string file_name;  ///< in out_dir
  std::string mesh;
};

struct WriteOutput {
  /// One garment: "garment" with its format's extension ("garment.obj"); an outfit:
  /// "outfit.glb" for a format holding several meshes, or empty when each garment has its
  /// file (see garments).
  std::string file_name;
  /// Per layer (Scene::layers' order), where it was written.
  std::vector<WrittenGarment> garments;
  /// Pierced faces the avatar still passes through or holds at the end, left out of the
  /// written garment (input face ids, sorted).
  std::vector<int> opened_document_faces;
  SkinTransferReport skin;
  double seconds = 0.0;
};

/// Write: the garment in the avatar's frame and units, in options.format, as the input's
/// document (vertex order, UVs, groups, materials): an OBJ with its material files, or a
/// GLB skinned over the avatar's skeleton when the avatar has one. An outfit (several
/// layers) is written as one file with a mesh (and skin) per garment, named by its layer,
/// in a format that holds several meshes unless options.split, else as a file per garment
/// (`<layer file stem>.<extension>`). Pierced faces still meeting the avatar are opened
/// first, so that what is written is free of it.
/// @throw OutputError when a file cannot be written.
WriteOutput run_write(const WriteInput& input, const WriteOptions& options, Progress& progress);

/// Writes a garment (normalized #Vg×3) as an OBJ in the avatar's frame and units.
void write_garment_obj(const std::string& path, const Scene& scene,
                       const NormalizedScene& normalized,
                       const Eigen::Ref<const MatrixX3d>& garment);
/// Writes an avatar (normalized #Va×3) as an OBJ in its file's frame and units.
void write_avatar_obj(const std::string& path, const Scene& scene,
                      const NormalizedScene& normalized, const Eigen::Ref<const MatrixX3d>& avatar);

}  // namespace gr
