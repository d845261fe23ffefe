#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/common/types.hpp"
#include "core/io/gltf_animation.hpp"
#include "core/io/obj_document.hpp"
#include "core/io/rig_files.hpp"

namespace gr {

/// The parsed glTF model (tinygltf), kept whole so a written file carries the input's
/// materials, textures and extra vertex attributes. Opaque outside core/io.
struct GltfModel;

/// One joint of a skin, in the asset's world frame at rest.
struct SkinJoint {
  std::string name;              ///< the node's name; `joint_<i>` when it has none
  int parent = -1;               ///< nearest ancestor that is a joint of the same skin, or -1
  Eigen::Matrix4d world;         ///< the joint node's world matrix in the rest pose
  Eigen::Matrix4d inverse_bind;  ///< as read (identity when the skin gives none)
  /// The node's own transform at rest, relative to its parent node, as the translation,
  /// rotation and scale an animation channel replaces (a node given by a matrix: its polar
  /// decomposition, shear dropped).
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  /// From the parent joint's frame (the world for a joint without one) to the joint's
  /// parent node's: the nodes between that are not joints of the skin, such as an armature.
  Eigen::Matrix4d parent_offset = Eigen::Matrix4d::Identity();
  /// The name of the joint's parent node when that is not a joint of the skin (empty:
  /// none, or no name).
  std::string parent_offset_name;
};

/// A skin: joints, and per document position the weight of each joint.
struct SkinBinding {
  std::vector<SkinJoint> joints;
  Eigen::MatrixXd weights;  ///< #J×#P; empty (0×0) when the mesh has no JOINTS_0/WEIGHTS_0
};

/// Where one merged glTF primitive sits in the document.
struct GltfPrimitive {
  int mesh = 0;            ///< the source mesh
  int source = 0;          ///< primitive index in the source mesh
  int first_position = 0;  ///< its first vertex among the document's positions
  int position_count = 0;
  int first_face = 0;  ///< its first triangle among the document's faces
  int face_count = 0;
};

/// One or more glTF meshes as read: their TRIANGLES primitives merged into `GltfAsset::document`
/// (position, texcoord and normal index of a corner are the vertex's merged index).
struct GltfDocument {
  std::shared_ptr<const GltfModel> model;
  int mesh = -1;          ///< the first mesh read
  std::string mesh_name;  ///< the names of the meshes read, joined by '+'
  std::string node_name;  ///< the node that places the first mesh read (`node_<i>` unnamed)
  std::vector<GltfPrimitive> primitives;
  bool has_tangents = false;        ///< some primitive had a TANGENT attribute
  std::optional<SkinBinding> skin;  ///< the skin of the node that places the mesh
};

/// A glTF mesh as an OBJ-like document (for the pipeline) plus what writing it back needs.
struct GltfAsset {
  ObjDocument document;
  GltfDocument gltf;
};

/// Reads one mesh of a glTF 2.0 file (binary `.glb` or JSON `.gltf`): the node named or
/// whose mesh is named `mesh_name`, else the first node with a skinned mesh, else the first
/// node with a mesh, in scene order. Every TRIANGLES primitive is merged (positions in
/// the world frame of the rest pose: node transforms applied, skinned meshes posed by
/// their skin); POINTS and LINES primitives are skipped with a warning. Texture
/// coordinates are stored flipped (v' = 1 - v) as an OBJ would hold them. Images are
/// kept as encoded bytes, never decoded.
/// @throw InputError naming the file for: a file that is neither GLB nor glTF JSON, a
///        parse error, a missing buffer or one outside the asset's folder, a strip or fan
///        primitive, an accessor out of range or of the wrong type, a sparse accessor,
///        Draco or meshopt compression, a missing mesh name (the message lists the
///        names), or a mesh with no triangle.
GltfAsset read_gltf(const std::string& path, const std::string& mesh_name = "");

/// Reads several meshes of one glTF file as read_gltf reads one, merged into one document
/// in the order named. With no name: every mesh that the first skinned mesh's skin drives,
/// in scene order, when `whole_skin` (a whole avatar: body, head, eyes), else as read_gltf.
/// @throw InputError as read_gltf, and for a mesh named twice or meshes of different skins.
GltfAsset read_gltf_meshes(const std::string& path, const std::vector<std::string>& mesh_names,
                           bool whole_skin = true);

/// The names of the meshes (or, for an unnamed mesh, of its node) that the scene's nodes
/// place, in scene order: the names read_gltf takes.
/// @throw InputError as read_gltf for a file that cannot be parsed.
std::vector<std::string> gltf_mesh_names(const std::string& path);

/// The names of the meshes read_gltf_meshes reads with no name and `whole_skin`.
/// @throw InputError as read_gltf for a file that cannot be parsed.
std::vector<std::string> gltf_skin_mesh_names(const std::string& path);

/// The skeleton of a skin: joint world positions (#J×3) and one bone per joint with a
/// parent (parent, joint).
/// @throw InputError naming `path` when the skin has no bone.
Skeleton skeleton_of_skin(const SkinBinding& skin, const std::string& path);

/// Writes `document` as a binary glTF (GLB) with `positions` (#P×3, document order, in the
/// frame the file should hold; stored as 32-bit floats as glTF requires). With `source`
/// (the document was read from glTF) its primitives, materials, textures (embedded) and
/// other vertex attributes are kept; without, one primitive with the document's texture
/// coordinates. Normals are recomputed (area-weighted per vertex over the faces that share
/// its position and input normal), tangents too when the source had them. With `skin`
/// (#J×#P weights) the mesh is skinned over its joints, written as nodes in the same rest
/// pose with inverse bind matrices that make the rest pose the written positions; each
/// vertex keeps its 4 largest weights, renormalized to sum 1.
/// @pre document faces index `positions`; `skin->weights` has #P columns and no negative
///      entry; every vertex of a face has a positive weight sum.
/// @throw OutputError when the file cannot be written.
void write_glb(const std::string& path, const ObjDocument& document, const GltfDocument* source,
               const Eigen::Ref<const MatrixX3d>& positions, const SkinBinding* skin);

/// One mesh of a GLB written with several (write_glb_meshes).
struct GlbMesh {
  std::string name;  ///< the mesh's and its node's name; empty: as write_glb names it
  const ObjDocument* document = nullptr;
  const GltfDocument* source = nullptr;  ///< as write_glb's source; null for an OBJ document
  MatrixX3d positions;                   ///< #P×3 of document, in the file's frame
  const SkinBinding* skin = nullptr;     ///< #J×#P weights of this document; null: unskinned
  /// Morph targets: per target, position deltas (#P×3, document order, in the skin's bind
  /// space), written with default weight 0.
  std::vector<MatrixX3d> morph_targets{};
};

/// Adds morph targets and animations to a GLB, keeping everything it holds: per entry, the
/// meshes of a document read from that very file (`layout`, whose primitives say where
/// each vertex is) get one target per matrix of deltas (#P×3 over the document's
/// positions), with default weight 0; clips are written as write_glb_meshes writes them.
/// The file is replaced atomically.
/// @throw InputError as read_gltf for a file that cannot be read; OutputError when it
///        cannot be written or a mesh already has morph targets.
struct GlbMorphTargets {
  const GltfDocument* layout = nullptr;
  std::vector<MatrixX3d> deltas;
};
void add_glb_animation(const std::string& path, const std::vector<GlbMorphTargets>& targets,
                       const std::vector<AnimationClip>& clips);

/// Writes several meshes as one binary glTF (GLB), an outfit's garments together: each
/// becomes its own glTF mesh and scene node, in the order given, written as write_glb
/// writes one (primitives, normals, tangents, copied attributes, influences). A mesh named
/// by neither `name` nor its source takes its OBJ file's stem, else "mesh"; names are not
/// made unique, and read_gltf finds the first of equal names. Materials, textures,
/// samplers and images are copied once per source model (`source->model`), each further
/// model's appended with its texture, sampler and image indices renumbered (the five
/// standard texture slots of a material, a texture's sampler and source; indices inside
/// material or texture extensions are copied as they are); extensionsUsed and
/// extensionsRequired are merged. The skinned meshes (a skin with weights) share one skin:
/// its joints are written once as nodes, from the first skinned mesh, and every skinned
/// mesh's node names it, with that mesh's own weights as its influences.
/// `animations` are written after the meshes: each channel drives the written node of its
/// name (a joint, or a mesh's node for morph weights); channels naming no written node are
/// left out.
/// @pre each mesh as write_glb's arguments; the skinned meshes' joints have the same world
///      matrices and parents; a weights channel has as many values per key as its mesh has
///      morph targets.
/// @throw OutputError naming the file when `meshes` is empty, a mesh has no document, two
///        skinned meshes' joints differ in count or names, or the file cannot be written.
void write_glb_meshes(const std::string& path, const std::vector<GlbMesh>& meshes,
                      const std::vector<AnimationClip>& animations = {});

}  // namespace gr
