#include "shrink/shrunk_avatar/skeleton_shrink.hpp"

#include <algorithm>
#include <chrono>
#include <limits>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>

#include "shrink/shrunk_avatar/shrink_certification.hpp"

namespace gr {

namespace {

struct Segment {
  Vector3d a, b;
  /// Parameter in [0, 1] of the point of the segment nearest to p.
  double parameter(const Vector3d& p) const {
    const Vector3d ab = b - a;
    const double length_sq = ab.squaredNorm();
    return length_sq > 0.0 ? std::clamp((p - a).dot(ab) / length_sq, 0.0, 1.0) : 0.0;
  }
  Vector3d at(double s) const { return a + s * (b - a); }
  double distance_sq(const Vector3d& p) const { return (at(parameter(p)) - p).squaredNorm(); }
};

/// A bone of the target skeleton's bone list, on `skeleton`'s joints (joints correspond
/// by index, so this is the same bone on either skeleton, in the same direction).
Segment bone_segment(const Skeleton& skeleton, const MatrixX2i& bones, Eigen::Index bone) {
  return {skeleton.joints.row(bones(bone, 0)).transpose(),
          skeleton.joints.row(bones(bone, 1)).transpose()};
}

void check_inputs(const TriangleMesh& avatar, const Skeleton& source, const Skeleton& target,
                  const Eigen::MatrixXd& weights, const SkeletonShrinkOptions& options) {
  if (target.bones.rows() == 0 || source.joints.rows() != target.joints.rows())
    throw std::invalid_argument(
        "shrink_to_skeleton: source and target skeletons must have the same joints and a bone");
  if (target.bones.minCoeff() < 0 || target.bones.maxCoeff() >= target.joints.rows())
    throw std::invalid_argument("shrink_to_skeleton: a bone index is out of range");
  if (weights.size() != 0 &&
      (weights.rows() != target.joints.rows() || weights.cols() != avatar.vertices.rows()))
    throw std::invalid_argument(fmt::format(
        "shrink_to_skeleton: skin weights are {}x{}, expected {} joints x {} vertices",
        weights.rows(), weights.cols(), target.joints.rows(), avatar.vertices.rows()));
  if (!(options.pullback > 0.0 && options.pullback <= 1.0) || options.max_halvings < 0)
    throw std::invalid_argument("shrink_to_skeleton: pullback must be in (0, 1]");
}

/// The bone a vertex belongs to: among the bones at its largest-weight joint (all bones
/// without weights), the nearest on the target skeleton.
Eigen::Index vertex_bone(const Skeleton& target, const Eigen::MatrixXd& weights, Eigen::Index v,
                         const Vector3d& p) {
  Eigen::Index joint = -1;
  if (weights.size() != 0 && weights.col(v).maxCoeff(&joint) <= 0.0) joint = -1;
  Eigen::Index best = -1;
  double best_distance = std::numeric_limits<double>::infinity();
  for (int pass = 0; pass < 2 && best < 0; ++pass)
    for (Eigen::Index b = 0; b < target.bones.rows(); ++b) {
      const bool at_joint = target.bones(b, 0) == joint || target.bones(b, 1) == joint;
      if (pass == 0 && joint >= 0 && !at_joint) continue;
      const double d = bone_segment(target, target.bones, b).distance_sq(p);
      if (d < best_distance) {
        best_distance = d;
        best = b;
      }
    }
  return best;
}

}  // namespace

ShrinkResult shrink_to_skeleton(const TriangleMesh& avatar, const TriangleMesh& garment,
                                const Skeleton& source_skeleton, const Skeleton& target_skeleton,
                                const Eigen::MatrixXd& skin_weights,
                                const SkeletonShrinkOptions& options) {
  check_inputs(avatar, source_skeleton, target_skeleton, skin_weights, options);
  const auto start_time = std::chrono::steady_clock::now();
  report_progress(options.progress, "shrink", 0.0);

  // Shrunk vertex = on_bone + pullback * offset.
  const Eigen::Index vertex_count = avatar.vertices.rows();
  MatrixX3d on_bone(vertex_count, 3), offset(vertex_count, 3);
  for (Eigen::Index v = 0; v < vertex_count; ++v) {
    const Vector3d p = avatar.vertices.row(v).transpose();
    const Eigen::Index bone = vertex_bone(target_skeleton, skin_weights, v, p);
    const Segment target = bone_segment(target_skeleton, target_skeleton.bones, bone);
    const Segment source = bone_segment(source_skeleton, target_skeleton.bones, bone);
    const double s = target.parameter(p);
    const Eigen::Quaterniond turn =
        Eigen::Quaterniond::FromTwoVectors(target.b - target.a, source.b - source.a);
    on_bone.row(v) = source.at(s).transpose();
    offset.row(v) = (turn * (p - target.at(s))).transpose();
  }

  ShrinkResult result;
  TriangleMesh shrunk{MatrixX3d(vertex_count, 3), avatar.faces};
  double pullback = options.pullback;
  std::optional<ShrinkConflict> conflict;
  for (int attempt = 0; attempt <= options.max_halvings; ++attempt, pullback *= 0.5) {
    shrunk.vertices = on_bone + pullback * offset;
    ++result.certifications;
    conflict = find_shrink_conflict(shrunk, garment);
    report_progress(options.progress, "shrink",
                    static_cast<double>(attempt + 1) / (options.max_halvings + 1));
    if (conflict) continue;
    result.vertices = shrunk.vertices;
    result.pullback = pullback;
    result.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
    report_progress(options.progress, "shrink", 1.0);
    return result;
  }
  throw NoValidShrinkError(
      fmt::format("no shrunk avatar is free of the garment: on the source skeleton with "
                  "pullback {:.3g} {}",
                  pullback * 2.0, conflict->describe()),
      *conflict);
}

}  // namespace gr
