#pragma once

#include "core/common/interrupter.hpp"
#include "core/common/types.hpp"
#include "core/io/rig_files.hpp"
#include "shrink/shrunk_avatar/shrink_result.hpp"

namespace gr {

/// How the skeleton shrink places vertices.
struct SkeletonShrinkOptions {
  /// Fraction of the way back from the source bone toward the vertex's own offset from its
  /// target bone: not zero, so no triangle collapses exactly onto a bone; small, so the
  /// shrunk avatar stays near the bones and leaves the garment room between body parts.
  /// Larger, the inflation has less far to go and takes fewer Newton steps, until the
  /// garment is caught between body parts as they grow (bench/results/
  /// parameter_choices.md). The pipeline inflates again from a fifth of the pullback when
  /// the inflation stalls.
  double pullback = 0.25;
  /// When the shrunk avatar still conflicts with the garment, the pullback is halved at
  /// most this many times before giving up (from 0.25, down to about 1e-3).
  int max_halvings = 8;
  /// Told stage "shrink" and one progress step per certification, and asked there whether
  /// to stop; null: none.
  Interrupter* interrupter = nullptr;
  /// Rounds of pulling the vertices of crossing faces toward their anchors (below), each
  /// followed by a certification, before the pullback is halved.
  int max_collapse_rounds = 24;
  /// Fraction of its remaining distance to its anchor a vertex of a crossing face moves in
  /// one round, in (0, 1): smaller moves fewer vertices farther than needed, larger needs
  /// fewer rounds.
  double collapse_step = 0.5;
};

/// The skeleton shrunk avatar. Each avatar vertex goes to its bone of the *source* skeleton
/// (the bone at its largest-weight joint nearest to it, or the nearest bone when there are
/// no weights or its weights are all zero), at the relative position along the bone it has
/// on the target skeleton, plus `pullback` times its offset from the target bone (turned by
/// the rotation from the target bone's direction to the source bone's).
///
/// A triangle whose corners land on two bones meeting at an angle spans the corner between
/// them (the armpit between shoulder and upper arm) and may cross the garment there, though
/// the bones themselves are inside it. So while the shrunk avatar's surface crosses the
/// garment, every vertex of a crossing face moves `collapse_step` of the way toward the
/// joint where the bones of the corners of its crossing faces meet, along the bones: toward
/// the end of its own bone nearer to that joint, and once there on along the next bone of
/// the path (a straight line from an arm to the spine would leave the sleeve through the
/// armpit); or toward its point on the bone when those corners share its bone. Each round
/// is certified; faces that shrink toward a joint stay non-degenerate, only smaller. When the
/// rounds run out or a garment vertex is inside, the pullback is halved and the rounds start again.
/// Certified with find_shrink_conflict.
/// @param avatar #V×3 / #F×3, normalized scene units (the target skeleton's frame).
/// @param garment in the same frame; the source skeleton sits inside it.
/// @param source_skeleton, target_skeleton normalized, joints corresponding by index; the
///        target's bone list is used for both.
/// @param skin_weights #J×#V, or empty (0×0).
/// @throw std::invalid_argument when the joint counts differ, there is no bone, or the
///        weights have the wrong shape; a pullback outside (0, 1], a collapse step outside
///        (0, 1), a negative round or halving count.
/// @throw NoValidShrinkError when every pullback tried conflicts with the garment.
/// @throw Interrupted from options.interrupter.
ShrinkResult shrink_to_skeleton(const TriangleMesh& avatar, const TriangleMesh& garment,
                                const Skeleton& source_skeleton, const Skeleton& target_skeleton,
                                const Eigen::MatrixXd& skin_weights,
                                const SkeletonShrinkOptions& options = {});

}  // namespace gr
