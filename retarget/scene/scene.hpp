#pragma once

#include <array>

#include <optional>
#include <string>
#include <vector>

#include "core/io/gltf_document.hpp"
#include "core/io/obj_document.hpp"
#include "core/io/rig_files.hpp"
#include "core/mesh/simulation_mesh.hpp"
#include "core/skinning/pose_transfer.hpp"
#include "retarget/run/run_control.hpp"

namespace gr {

/// A garment of an outfit beyond the first (ScenePaths::more_garments): its own file and
/// what belongs to it alone.
struct GarmentPaths {
  std::string garment;
  std::string garment_mesh{};  ///< glTF: the mesh (or node) to read; empty: the default
  std::string no_fit{};        ///< 0-based vertex ids of this garment's document
  /// Its source skeleton, when its file is in another frame than the first garment's: it is
  /// moved onto the first garment's source skeleton. Empty: the first garment's frame.
  std::string source_skeleton{};
  std::string source_body{};  ///< the body it was made on, in its own frame
};

/// Where a retargeting scene's files are. Only garment and avatar are required.
struct ScenePaths {
  std::string garment;
  std::string avatar;
  std::string source_skeleton;  ///< with target_skeleton, or neither
  std::string target_skeleton;
  std::string skin_weights;  ///< #joints × #avatar OBJ vertices; needs skeletons
  std::string no_fit;        ///< 0-based garment OBJ vertex ids
  // Initialized so brace lists that stop at no_fit stay warning-free.
  std::string garment_mesh{};  ///< glTF garment: the mesh (or node) to read; empty: the default
  /// glTF avatar: the meshes (or nodes) to read, merged; empty: every mesh its skin drives
  std::vector<std::string> avatar_meshes{};
  std::string joint_map{};    ///< glTF skins: source joint name -> target joint name
  std::string source_body{};  ///< the body the garment was made on, in the garment's frame
  /// glTF source body: its meshes, merged; empty: every mesh its skin drives but the garment
  std::vector<std::string> source_body_meshes{};
  /// An outfit: the garments worn with the first, each a layer (any order; the run
  /// measures inside to outside). Empty: one garment.
  std::vector<GarmentPaths> more_garments{};
};

/// One garment of an outfit as read: its own document, and where it lies in the scene's
/// merged garment document.
struct GarmentLayer {
  std::string name;  ///< its glTF mesh's name, else its file's stem; unique in the scene
  /// Its own written files' stem (`<stem>.obj`, `<stem>.no-fit.txt`): the name with only
  /// letters, digits, '-', '_' and '.', unique, never one of the result folder's own names.
  std::string file_stem;
  std::string path;
  std::string mesh;  ///< the glTF mesh read; empty for OBJ
  /// Its document, positions in the first garment's frame.
  ObjDocument document;
  std::optional<GltfDocument> gltf;
  /// Its file's frame → the first garment's (identity for the first, and for a garment
  /// given without a source skeleton of its own).
  Eigen::Matrix4d to_first_frame = Eigen::Matrix4d::Identity();
  int first_position = 0;  ///< its first position in Scene::garment_document
  int position_count = 0;
  int first_face = 0;  ///< its first face in Scene::garment_document
  int face_count = 0;
  /// A skirt: its boundary loops take a virtual bone between the legs, and its no-fit list
  /// is inferred below the hips.
  bool skirt = false;
};

/// How the garment's skin was turned from its own pose into the target's.
struct GarmentPose {
  std::vector<std::string> joint_names;  ///< the garment skin's joints, in its order
  std::vector<Eigen::Isometry3d> motions;
  SkinningMethod method = SkinningMethod::kLinearBlend;
};

/// A scene as read and checked, in the files' own units and frames.
struct Scene {
  ObjDocument garment_document;
  SimulationMesh garment;
  ObjDocument avatar_document;
  SimulationMesh avatar;
  std::optional<Skeleton> source_skeleton;
  std::optional<Skeleton> target_skeleton;
  /// The skeletons' joint names when skins gave them (in their joint order); else empty.
  std::vector<std::string> joint_names;
  /// The (copy, original) garment vertex pairs of the edges split for the solver (the
  /// prepare stage's split_non_manifold_edges; see GarmentScene::ties).
  std::vector<std::array<int, 2>> garment_ties;
  Eigen::MatrixXd skin_weights;  ///< #joints × #avatar welded vertices; empty when not given
  std::vector<int> no_fit;       ///< welded garment vertex ids
  std::vector<std::string> warnings;
  std::optional<GltfDocument> garment_gltf;  ///< set when the garment was read from glTF
  std::optional<GltfDocument> avatar_gltf;   ///< set when the avatar was read from glTF
  /// The garments of the scene in the order given, merged in that order into
  /// garment_document and garment (no vertex shared between two); one for one garment.
  std::vector<GarmentLayer> layers;
  /// Per simulation garment face, its layer (fixed when read: the write's opened faces
  /// leave the document, not the simulation mesh).
  std::vector<int> garment_face_layer;
  /// The avatar's skin over its whole skeleton, weights #J×#avatar document positions:
  /// its glTF skin, else the target skeleton with the skin weights file; unset without.
  std::optional<SkinBinding> avatar_skin;
  /// Set when the garment was turned into the target's pose before the solve
  /// (pose_garment): per joint of its skin, its name and motion.
  std::optional<GarmentPose> garment_pose;
};

/// Per simulation garment vertex, 1 where its layer is a skirt (GarmentLayer::skirt); empty
/// when no layer is.
std::vector<char> skirt_vertices(const Scene& scene);

/// Per face of `document` (Scene::garment_document), the layer it belongs to.
std::vector<int> layer_of_document_faces(const Scene& scene);
/// Per face of the simulation garment (Scene::garment), the layer it belongs to
/// (Scene::garment_face_layer).
std::vector<int> layer_of_garment_faces(const Scene& scene);

/// Every input file the paths name (the empty ones left out), garment and avatar first.
std::vector<std::string> input_files(const ScenePaths& paths);

/// Checks every input file before any is opened: each must be a regular file of at most
/// `max_input_mb` MB (see require_regular_file).
/// @throw InputError naming the first file that is not.
void check_input_files(const ScenePaths& paths, double max_input_mb);

/// Refuses a scene beyond `limits`' face count (garment and avatar each) or estimated
/// memory (estimated_peak_memory_mb), before any costly work.
/// @return the memory estimate, MB.
/// @throw InputError naming the file and the limit.
double require_within_limits(const Scene& scene, const RunLimits& limits);

/// Reads and checks every file of a scene. Garment and avatar may be OBJ or glTF (see
/// read_gltf); without skeleton files, two skinned glTF files give the skeletons (their
/// skins' joints matched by name, through the joint map when given) and the avatar's skin
/// gives the skin weights.
/// @throw InputError for any bad file or inconsistency between files (a skeleton without
///        its partner, skeletons that do not correspond, skin weights without skeletons
///        or of the wrong shape, a garment or avatar with no face, skins whose joints do
///        not match, a joint map without two skins).
Scene load_scene(const ScenePaths& paths);

/// The avatar's skin for a written GLB: `scene.avatar_skin`, else its skeleton (a glTF
/// skin without weights, or the target skeleton) with every vertex bound to its nearest
/// bone (nearest_bone_weights); unset when the avatar has no skeleton.
/// @throw InputError when a glTF skin without weights has no bone.
std::optional<SkinBinding> avatar_skin_for_export(const Scene& scene);

}  // namespace gr
