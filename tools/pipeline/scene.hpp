#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/io/obj_document.hpp"
#include "core/io/rig_files.hpp"
#include "core/mesh/simulation_mesh.hpp"

namespace gr {

/// Where a retargeting scene's files are. Only garment and avatar are required.
struct ScenePaths {
  std::string garment;
  std::string avatar;
  std::string source_skeleton;  ///< with target_skeleton, or neither
  std::string target_skeleton;
  std::string skin_weights;  ///< #joints × #avatar OBJ vertices; needs skeletons
  std::string no_fit;        ///< 0-based garment OBJ vertex ids
  std::string source_body;   ///< the body the garment was made on, in the garment's frame
};

/// A scene as read and checked, in the files' own units and frames.
struct Scene {
  ObjDocument garment_document;
  SimulationMesh garment;
  ObjDocument avatar_document;
  SimulationMesh avatar;
  std::optional<Skeleton> source_skeleton;
  std::optional<Skeleton> target_skeleton;
  Eigen::MatrixXd skin_weights;  ///< #joints × #avatar welded vertices; empty when not given
  std::vector<int> no_fit;       ///< welded garment vertex ids
  std::vector<std::string> warnings;
};

/// Reads and checks every file of a scene.
/// @throw InputError for any bad file or inconsistency between files (a skeleton without
///        its partner, skeletons that do not correspond, skin weights without skeletons
///        or of the wrong shape, a garment or avatar with no face).
Scene load_scene(const ScenePaths& paths);

}  // namespace gr
