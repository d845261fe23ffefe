#pragma once

#include <string>

#include "core/common/interrupter.hpp"
#include "core/common/types.hpp"
#include "core/io/rig_files.hpp"

namespace gr {

/// How distances from a vertex to the bones are measured.
enum class BindingMethod {
  /// Shortest paths through the avatar's interior voxels (Dionne and de Lasa 2013): a bone
  /// reaches a vertex only through the body, never through the air between limbs.
  kGeodesic,
  /// Straight-line distance to each bone whose closest point the vertex sees through the
  /// interior (the segment between them stays inside), the others left out.
  kVisible,
  /// Bone heat diffusion over the surface (Baran and Popović 2007, see bone_heat): each
  /// vertex is heated by its nearest visible bone (as kVisible sees them) and the heat of
  /// each bone spreads along the mesh by the cotangent Laplacian.
  kHeat,
};

/// "geodesic", "visible" or "heat".
const char* to_string(BindingMethod method);

/// How automatic skin weights are computed.
struct BindingOptions {
  BindingMethod method = BindingMethod::kGeodesic;
  /// Voxels along the avatar's largest bounding-box side (the voxel size follows, so the
  /// result does not depend on the file's units).
  int resolution = 128;
  /// Weight of a bone at distance d (plus one voxel): proportional to d^-falloff.
  double falloff = 8.0;
  /// Bones farther than this multiple of the nearest bone's distance (plus one voxel) get
  /// no weight.
  double distance_ratio = 1.5;
  /// Most joints weighting one vertex.
  int max_influences = 4;
  /// The skeleton's root joint: each bone's weight goes to its joint nearer the root (the
  /// joint whose transform moves the bone).
  int root_joint = 0;
  /// A joint with no child bone, or whose child bones on average turn away from its parent
  /// bone by more than this angle (degrees; the neck, whose children are the collarbones),
  /// gets an end segment continuing its parent bone, weighted to the joint itself: the
  /// hand, foot and head beyond the last joint.
  double end_angle_degrees = 135.0;
  /// Length of an end segment, in lengths of the parent bone.
  double end_length = 1.0;
  /// Told stages "binding grid" and "binding" and their progress, and asked between parts
  /// whether to stop; null: none.
  Interrupter* interrupter = nullptr;
};

/// A bone or an end segment of a skeleton (see BindingOptions::end_angle_degrees), in the
/// skeleton's units.
struct BoneSegment {
  Vector3d a, b;  ///< for a bone, a is its joint nearer the root; for an end segment, its joint
  int owner = 0;  ///< the joint its skin weight goes to: a's joint
  /// For an end segment, the index (in the same list) of the bone it continues; -1 for a bone.
  int continues = -1;

  Vector3d closest_point(const Vector3d& p) const;
  double distance(const Vector3d& p) const { return (closest_point(p) - p).norm(); }
};

/// The skeleton's bones, each directed away from the root (BindingOptions::root_joint;
/// joints no bone path joins to it start their own tree at their lowest-numbered joint),
/// followed by the end segments. Bones joining a joint to itself are left out.
/// @pre bone indices in range and root_joint a joint (bind_skeleton checks both).
std::vector<BoneSegment> skeleton_segments(const Skeleton& skeleton, const BindingOptions& options);

/// Automatic skin weights and how they were found.
struct Binding {
  /// #J×#V, each column non-negative and summing to 1, at most max_influences non-zeros: the
  /// same layout as a skin-weights file (read_skin_weights).
  Eigen::MatrixXd weights;
  double voxel_size = 0.0;        ///< in the avatar's units
  long long interior_voxels = 0;  ///< voxels inside the avatar (generalized winding number)
  int segments = 0;               ///< bones plus end segments
  /// Vertices bound through interior voxels near them, through their mesh neighbours (a thin
  /// or open part with no interior voxel within two voxels: the weights of the nearest bound
  /// vertex of the same connected part, along its edges), and by straight-line distance (a
  /// part with no bound vertex at all). For kHeat: vertices that see a bone, vertices heated
  /// through the surface alone, and vertices of parts where no vertex sees a bone.
  int vertices_through_interior = 0;
  int vertices_through_neighbours = 0;
  int vertices_by_straight_line = 0;
  /// Vertices of stray islands (regions of one dominant joint bordered only by regions of
  /// joints neither theirs nor next to it in the skeleton: a hand resting on a thigh reached
  /// by the thigh's bone), bound again through their mesh neighbours (not for kHeat).
  int vertices_rebound = 0;
  double seconds = 0.0;
};

/// Computes skin weights for `avatar` from `skeleton` alone. The avatar's interior is
/// voxelized by the generalized winding number (so open, overlapping and multi-part meshes
/// get a solid that does not leak), each bone (and end segment, see BindingOptions) is
/// rasterized into the interior voxels nearest it, and each vertex is weighted by its
/// distance to the bones (BindingOptions::method) with a power falloff over the nearest
/// ones; kHeat instead diffuses each bone's heat over the surface (bone_heat), falling
/// back to the power falloff for parts where no vertex sees a bone. The largest
/// max_influences joints are kept. Deterministic: the same inputs give the same weights with
/// any thread count.
/// @param avatar #V×3 / #F×3, any units; faces need a consistent orientation per part.
/// @param skeleton joints (#J×3) in the avatar's frame and units; bones (#B×2) into them.
/// @return weights #J×#V as a skin-weights file holds them.
/// @throw std::invalid_argument when the avatar has no face or an index out of range, the
///        skeleton has no bone or a bone index out of range, the root joint is out of range,
///        or an option is out of its range (resolution < 8, falloff <= 0, ratio < 1,
///        influences < 1, end length < 0).
/// @throw std::runtime_error when the heat system cannot be factored (kHeat).
/// @throw Interrupted from options.interrupter.
Binding bind_skeleton(const TriangleMesh& avatar, const Skeleton& skeleton,
                      const BindingOptions& options = {});

/// How far apart two sets of skin weights are.
struct WeightAgreement {
  /// Mean over vertices of 1 - |a - b|_1 / 2 for columns normalized to sum 1: 1 for equal
  /// weights, 0 for weights on disjoint joints.
  double mean_agreement = 0.0;
  /// Share of vertices whose largest-weight joint is the same in both.
  double dominant_match = 0.0;
  int vertices = 0;  ///< vertices compared: those with a positive weight in both
};

/// Compares two #J×#V skin-weight matrices column by column.
/// @throw std::invalid_argument when the shapes differ.
WeightAgreement compare_skin_weights(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b);

}  // namespace gr
