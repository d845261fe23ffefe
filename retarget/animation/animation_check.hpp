#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "retarget/animation/animation_clips.hpp"
#include "validate/certify/validation.hpp"

namespace gr {

/// Skinned garments and their avatar, as read, ready to be posed together through clips.
struct AnimatedScene {
  struct Part {
    std::string path;
    GltfAsset asset;    ///< as read: rest positions, skin
    TriangleMesh mesh;  ///< faces as the validator reads them; vertices at rest
    SkinnedMesh skinned;
    std::vector<MeshMorphTargets> morphs;
    std::vector<AnimationClip> own_clips;  ///< the clips of the part's own file
  };
  std::vector<Part> garments;
  Part avatar;
  /// Per garment, its self-intersecting face pairs at rest (sorted): counted apart in every
  /// frame, as the rest check already reports them.
  std::vector<std::vector<FacePair>> rest_self_pairs;
  /// Per garment pair (first < second, in order), its crossing pairs at rest (sorted).
  std::vector<std::vector<FacePair>> rest_layer_pairs;
  /// The avatar's own self-intersecting face pairs at rest (sorted).
  std::vector<FacePair> rest_avatar_self_pairs;
};

/// Reads the skinned garments (each its mesh of garment_meshes, or the default) and the
/// avatar (its meshes, merged) for posing, and finds the pairs that cross at rest.
/// @throw InputError for a file that cannot be read, or a garment or avatar with no skin
///        (the message says that animation needs skinned glTF files).
AnimatedScene read_animated_scene(const std::vector<std::string>& garment_paths,
                                  const std::vector<std::string>& garment_meshes,
                                  const std::string& avatar_path,
                                  const std::vector<std::string>& avatar_meshes);

/// One frame checked: intersecting pairs, each kind counted apart.
struct FrameFindings {
  double time = 0.0;
  std::size_t avatar_pairs = 0;  ///< garment–avatar
  std::size_t self_pairs = 0;    ///< garment self pairs not crossing at rest
  std::size_t layer_pairs = 0;   ///< garment–garment pairs not crossing at rest
  /// Where the garments cross: the avatar's own pairs not crossing at rest (its skin
  /// passing through itself, as in a closed elbow, leaves the cloth between no room). Not
  /// in total(): it says why, not what.
  std::size_t avatar_self_pairs = 0;
  /// Per garment, its faces in the pairs counted (sorted, each once).
  std::vector<std::vector<int>> crossing_faces;
  std::size_t total() const { return avatar_pairs + self_pairs + layer_pairs; }
};

/// Checks one frame exactly: each posed garment against the posed avatar, itself and the
/// other garments, pairs crossing at rest counted apart. `time` is copied into the result.
/// @pre garments in the scene's order, each with its part's faces.
FrameFindings check_posed_frame(const AnimatedScene& scene,
                                const std::vector<TriangleMesh>& garments,
                                const TriangleMesh& avatar, double time);

/// A clip played and every sampled frame checked exactly.
struct ClipFindings {
  std::string clip;
  std::string file;
  double fps = 0.0;
  ClipTranslations translations = ClipTranslations::kAll;
  int avatar_driven_joints = 0;
  std::vector<int> garment_driven_joints;
  std::vector<std::string> unmatched_nodes;  ///< clip nodes the avatar's skin lacks
  std::vector<FrameFindings> frames;
  double seconds = 0.0;
  /// How far a garment joint moves from the avatar joint of its name, over the frames (file
  /// units), among the joints that coincide at rest; the joint and frame where it is
  /// largest. Apart, the clip poses the garment by a rig placed otherwise than the avatar's
  /// (an armature one file has and the other baked into its root joint), so the frames
  /// checked are not those an engine plays with the garment bound to the avatar's joints.
  double joint_drift = 0.0;
  std::string drift_joint;
  std::size_t drift_frame = 0;
  double drift_limit = 0.0;  ///< kMaxJointDrift of the avatar's size
  bool rigs_agree() const { return joint_drift <= drift_limit; }
  /// Every frame free, and the rigs in agreement.
  bool certified() const { return crossing_frames() == 0 && rigs_agree(); }

  std::size_t crossing_frames() const;
  /// Of the crossing frames, those where the avatar crosses itself too.
  std::size_t avatar_crossing_itself_frames() const;
  /// The first frame with an intersection, and the one with the most pairs; none when every
  /// frame is free.
  std::optional<std::size_t> first_crossing() const;
  std::optional<std::size_t> worst_frame() const;
};

/// The joint drift (ClipFindings::joint_drift) allowed, as a share of the avatar's size
/// (its bounding box's largest side): far above the rounding of joint transforms, far below
/// any move a rig placed otherwise makes.
constexpr double kMaxJointDrift = 1e-3;
/// Garment and avatar joints of one name this close at rest (share of the avatar's size)
/// are one joint of one rig.
constexpr double kSameJointAtRest = 1e-4;

/// The meshes of every sampled frame of a clip as check_clip posed and checked them, in the
/// files' frame and units.
struct ClipPoses {
  std::vector<MatrixX3d> avatar;                 ///< per frame, #Va×3
  std::vector<std::vector<MatrixX3d>> garments;  ///< per frame, per garment #Vg×3
};

/// Samples `clip` at `fps` from its start to its end, poses the avatar and garments by
/// their skins (joints matched by name; a garment's morph weights from the clip of the same
/// name in its own file, where it has one) and checks every frame exactly: garment–avatar,
/// self and layer pairs (validate_meshes). Frames run in parallel. With `poses`, the posed
/// meshes of every frame are kept there too (for the report page's frame slider). With
/// `explain`, a frame that crosses is also checked for the avatar crossing itself.
/// @pre fps > 0.
ClipFindings check_clip(const AnimatedScene& scene, const ChosenClip& clip, double fps,
                        ClipPoses* poses = nullptr, bool explain = true);

/// The report section of one clip: counts, the first and worst frames, and per frame its
/// time and pair counts.
nlohmann::ordered_json to_json(const ClipFindings& findings);

/// One line for the user: frames, crossing frames, the first and the worst.
std::string clip_summary(const ClipFindings& findings);

}  // namespace gr
