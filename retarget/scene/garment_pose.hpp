#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "core/skinning/pose_transfer.hpp"
#include "retarget/scene/scene.hpp"

namespace gr {

/// Which pose the solve starts the garment in.
enum class PoseMode {
  kTarget,   ///< the target's: turned by its own skin before the shrink, where it can be
  kAsGiven,  ///< the pose its file shows
};

const char* to_string(PoseMode mode);
/// @throw std::invalid_argument for a name other than "target" or "as-given".
PoseMode parse_pose_mode(const std::string& name);

/// What the pose step did (report.json `pose`).
struct PoseReport {
  PoseMode mode = PoseMode::kAsGiven;
  bool posed = false;
  std::string reason;  ///< why the garment kept its pose, when it did
  SkinningMethod method = SkinningMethod::kLinearBlend;
  int joints = 0;
  double largest_turn_degrees = 0.0;  ///< the largest turn of a joint that holds some of it
  /// Crossings the turn made, pushed apart after it (all of them, or the pose is kept).
  int untangled_pairs = 0;
  /// The pose step's own change of shape, scale free (ShapeChange).
  double mean_edge_change = 0.0;
  double p95_edge_change = 0.0;
  bool source_body_posed = false;
};

nlohmann::json to_json(const PoseReport& report);

/// Brings a skinned glTF garment from its own skeleton's pose into the target skeleton's
/// (pose_transfer_motions on the skeletons matched from the two skins), by its own skin
/// weights: its document and simulation positions and the source skeleton move; the
/// motions are kept in scene.garment_pose, so that a source body of the same skin follows.
/// Crossings of its own that the turn makes (exact check) are pushed apart
/// (untangle_crossings). A garment without its own skin, an outfit, skeletons given as
/// files, or a garment left crossing itself where it did not before keep their pose (the
/// report says why).
PoseReport pose_garment(Scene& scene, PoseMode mode, SkinningMethod method);

/// `positions` (#P×3, a document of a skinned glTF file) moved by scene.garment_pose, when
/// the file's skin has the garment skin's joints (same names, same order); false otherwise.
bool pose_like_garment(const Scene& scene, const SkinBinding& skin, MatrixX3d& positions);

}  // namespace gr
