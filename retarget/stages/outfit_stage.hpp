#pragma once

#include <optional>
#include <string>
#include <vector>

#include "garment/layers/hidden_faces.hpp"
#include "retarget/report.hpp"
#include "retarget/run/progress.hpp"
#include "retarget/scene/normalization.hpp"
#include "validate/certify/certificate.hpp"

namespace gr {

/// The layers named inside to outside (each by GarmentLayer::name, its path as given or its
/// file name) as layer ids; empty names give an empty order (measure it).
/// @throw InputError naming the unknown, repeated or missing garment.
std::vector<int> resolve_layer_order(const Scene& scene, const std::vector<std::string>& names);

/// Marks the skirts among the layers (GarmentLayer::skirt): every layer with `all`, else
/// those named (as in resolve_layer_order).
/// @throw InputError naming an unknown garment.
void mark_skirts(Scene& scene, bool all, const std::vector<std::string>& names);

struct OutfitInput {
  const Scene& scene;
  const NormalizedScene& normalized;
  const MatrixX3d& garment;  ///< the written outfit (normalized #Vg×3, every layer)
  const TriangleMesh* source_body = nullptr;  ///< normalized; null: none given
  const Certificate& certificate;             ///< of the written garments, a layer each
  /// Per garment face, whether it lies in a tangle of crossings the input came with
  /// (InheritedCrossings::tangles): the layers have no order there. Empty: none.
  std::vector<char> tangled_faces;
  std::string out_dir;    ///< where the files are written (staging)
  std::string final_dir;  ///< where they will be (named in the report)
};

struct OutfitOptions {
  std::vector<int> given_order;  ///< inside to outside (resolve_layer_order); empty: measure
  bool write_avatar = false;     ///< also write the avatar without its hidden faces
  /// Source distances closer than this have no order (rays_reordered_from_source),
  /// normalized units.
  double order_tolerance = 0.0;
  HiddenFaceOptions hidden;
};

struct OutfitOutput {
  OutfitReport report;                     ///< every part but the layers' own (the caller's)
  std::vector<int> hidden_document_faces;  ///< avatar document faces, sorted
};

/// Outfit: the layers' order from inside to outside, given or measured on the source (rays
/// from the source skeleton's bones, else from the source body, stopped where they enter
/// the body again), and whether the written outfit keeps it on the avatar; the avatar
/// faces every garment hides, written to out_dir/hidden-avatar-faces.txt, and with
/// write_avatar the avatar without them (avatar.glb for a glTF avatar, skinned as it was,
/// else avatar.obj).
/// @throw OutputError when a file cannot be written.
OutfitOutput run_outfit(const OutfitInput& input, const OutfitOptions& options, Progress& progress);

}  // namespace gr
