#include "shrink/shrunk_avatar/skeleton_shrink.hpp"

#include <algorithm>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <tuple>
#include <vector>

#include <fmt/format.h>

#include "core/common/stopwatch.hpp"
#include "shrink/shrunk_avatar/shrink_certification.hpp"
#include "validate/checks/mesh_intersections.hpp"

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
    throw std::invalid_argument(
        fmt::format("shrink_to_skeleton: skin weights are {}x{}, expected {} joints x {} vertices",
                    weights.rows(), weights.cols(), target.joints.rows(), avatar.vertices.rows()));
  if (!(options.pullback > 0.0 && options.pullback <= 1.0) || options.max_halvings < 0)
    throw std::invalid_argument("shrink_to_skeleton: pullback must be in (0, 1]");
  if (!(options.collapse_step > 0.0 && options.collapse_step < 1.0) ||
      options.max_collapse_rounds < 0)
    throw std::invalid_argument(
        "shrink_to_skeleton: collapse step must be in (0, 1) and rounds non-negative");
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

/// Each avatar vertex on its source bone: shrunk position = on_bone + pullback * offset.
struct BonePlacement {
  MatrixX3d on_bone;               ///< #V×3: the vertex's point on its source bone
  MatrixX3d offset;                ///< #V×3: its offset from the target bone, turned
  std::vector<Eigen::Index> bone;  ///< its bone (row of the target's bone list)
};

BonePlacement place_on_bones(const TriangleMesh& avatar, const Skeleton& source_skeleton,
                             const Skeleton& target_skeleton, const Eigen::MatrixXd& weights) {
  const Eigen::Index vertex_count = avatar.vertices.rows();
  BonePlacement placement{MatrixX3d(vertex_count, 3), MatrixX3d(vertex_count, 3),
                          std::vector<Eigen::Index>(static_cast<std::size_t>(vertex_count))};
  for (Eigen::Index v = 0; v < vertex_count; ++v) {
    const Vector3d p = avatar.vertices.row(v).transpose();
    const Eigen::Index bone = vertex_bone(target_skeleton, weights, v, p);
    const Segment target = bone_segment(target_skeleton, target_skeleton.bones, bone);
    const Segment source = bone_segment(source_skeleton, target_skeleton.bones, bone);
    const double s = target.parameter(p);
    const Eigen::Quaterniond turn =
        Eigen::Quaterniond::FromTwoVectors(target.b - target.a, source.b - source.a);
    placement.on_bone.row(v) = source.at(s).transpose();
    placement.offset.row(v) = (turn * (p - target.at(s))).transpose();
    placement.bone[static_cast<std::size_t>(v)] = bone;
  }
  return placement;
}

/// Bones between every two joints (breadth-first over the bone graph); joints in separate
/// pieces are #J apart.
Eigen::MatrixXi joint_hops(const Skeleton& skeleton) {
  const auto joint_count = static_cast<int>(skeleton.joints.rows());
  std::vector<std::vector<int>> neighbours(static_cast<std::size_t>(joint_count));
  for (Eigen::Index b = 0; b < skeleton.bones.rows(); ++b) {
    neighbours[static_cast<std::size_t>(skeleton.bones(b, 0))].push_back(skeleton.bones(b, 1));
    neighbours[static_cast<std::size_t>(skeleton.bones(b, 1))].push_back(skeleton.bones(b, 0));
  }
  Eigen::MatrixXi hops = Eigen::MatrixXi::Constant(joint_count, joint_count, joint_count);
  for (int from = 0; from < joint_count; ++from) {
    std::vector<int> queue{from};
    hops(from, from) = 0;
    for (std::size_t head = 0; head < queue.size(); ++head)
      for (int next : neighbours[static_cast<std::size_t>(queue[head])])
        if (hops(from, next) == joint_count) {
          hops(from, next) = hops(from, queue[head]) + 1;
          queue.push_back(next);
        }
  }
  return hops;
}

/// Pulls the vertices of crossing faces toward the joints where their bones meet.
class CrossingCollapse {
 public:
  CrossingCollapse(const TriangleMesh& avatar, const Skeleton& source,
                   const BonePlacement& placement)
      : faces_(avatar.faces), source_(source), placement_(placement), hops_(joint_hops(source)),
        bone_(placement.bone), collapsed_(static_cast<std::size_t>(avatar.vertices.rows()), 0) {}

  /// Moves every vertex of the listed avatar faces `step` of the way toward its anchor.
  void apply(const FacePairList& crossing, double step, MatrixX3d& vertices) {
    // The bones of every crossing face each vertex is a corner of.
    std::map<int, std::vector<Eigen::Index>> bones_met;
    int previous_face = -1;
    for (const FacePair& pair : crossing.pairs) {
      if (pair.first == previous_face) continue;  // pairs come sorted by avatar face
      previous_face = pair.first;
      for (int c = 0; c < 3; ++c) {
        std::vector<Eigen::Index>& bones = bones_met[faces_(pair.first, c)];
        for (int other = 0; other < 3; ++other) bones.push_back(bone_of(faces_(pair.first, other)));
      }
    }
    for (auto& [v, bones] : bones_met) {
      std::sort(bones.begin(), bones.end());
      bones.erase(std::unique(bones.begin(), bones.end()), bones.end());
      const Vector3d x = vertices.row(v).transpose();
      if (bones.size() == 1) {
        const Vector3d anchor = placement_.on_bone.row(v).transpose();
        vertices.row(v) = (anchor + (1.0 - step) * (x - anchor)).transpose();
      } else {
        vertices.row(v) = toward_meeting_joint(v, meeting_joint(bones, x), x, step).transpose();
      }
      collapsed_[static_cast<std::size_t>(v)] = 1;
    }
  }

  int collapsed_count() const {
    return static_cast<int>(std::count(collapsed_.begin(), collapsed_.end(), 1));
  }
  void reset() {
    std::fill(collapsed_.begin(), collapsed_.end(), 0);
    bone_ = placement_.bone;
  }

 private:
  Eigen::Index bone_of(int v) const { return bone_[static_cast<std::size_t>(v)]; }

  /// Where a vertex moves in one round toward the joint `meeting`: along the skeleton, not
  /// straight (a straight line from an arm to the spine leaves the sleeve through the
  /// armpit). It heads for the end of its bone nearer to the meeting joint; once there, it
  /// takes the next bone of the path as its own.
  Vector3d toward_meeting_joint(int v, Eigen::Index meeting, const Vector3d& x, double step) {
    Eigen::Index& bone = bone_[static_cast<std::size_t>(v)];
    const auto hops_to = [&](Eigen::Index joint) { return hops_(joint, meeting); };
    const Eigen::Index a = source_.bones(bone, 0), b = source_.bones(bone, 1);
    const Eigen::Index end = hops_to(a) <= hops_to(b) ? a : b;
    const Vector3d target = source_.joints.row(end).transpose();
    const Vector3d moved = target + (1.0 - step) * (x - target);
    const double length = (source_.joints.row(a) - source_.joints.row(b)).norm();
    if (end == meeting || (moved - target).norm() > kArrived * length) return moved;
    // Arrived at the bone's end (all but: vertices never meet exactly): on along the next
    // bone of a shortest path.
    for (Eigen::Index next = 0; next < source_.bones.rows(); ++next) {
      const Eigen::Index p = source_.bones(next, 0), q = source_.bones(next, 1);
      const Eigen::Index far = p == end ? q : q == end ? p : -1;
      if (far >= 0 && hops_to(far) < hops_to(end)) {
        bone = next;
        break;
      }
    }
    return moved;
  }

  /// A vertex this close to its bone's end (in bone lengths) has arrived there.
  static constexpr double kArrived = 1e-3;

  /// The source joint where `bones` meet: fewest bones from the farthest of them (the
  /// shared joint of two bones that touch, the middle of the path between two that do not),
  /// then fewest in total, then nearest to x.
  Eigen::Index meeting_joint(const std::vector<Eigen::Index>& bones, const Vector3d& x) const {
    std::tuple<int, int, double> best{std::numeric_limits<int>::max(), 0, 0.0};
    Eigen::Index best_joint = 0;
    for (Eigen::Index j = 0; j < source_.joints.rows(); ++j) {
      int farthest = 0, total = 0;
      for (Eigen::Index bone : bones) {
        const int hops =
            std::min(hops_(j, source_.bones(bone, 0)), hops_(j, source_.bones(bone, 1)));
        farthest = std::max(farthest, hops);
        total += hops;
      }
      const std::tuple<int, int, double> score{
          farthest, total, (source_.joints.row(j).transpose() - x).squaredNorm()};
      if (score < best) {
        best = score;
        best_joint = j;
      }
    }
    return best_joint;
  }

  const MatrixX3i& faces_;
  const Skeleton& source_;
  const BonePlacement& placement_;
  Eigen::MatrixXi hops_;
  std::vector<Eigen::Index> bone_;  ///< each vertex's bone, moved on along paths to joints
  std::vector<char> collapsed_;
};

}  // namespace

ShrinkResult shrink_to_skeleton(const TriangleMesh& avatar, const TriangleMesh& garment,
                                const Skeleton& source_skeleton, const Skeleton& target_skeleton,
                                const Eigen::MatrixXd& skin_weights,
                                const SkeletonShrinkOptions& options) {
  check_inputs(avatar, source_skeleton, target_skeleton, skin_weights, options);
  const Stopwatch stopwatch;
  Interrupter& interrupter = or_null(options.interrupter);
  interrupter.start("shrink");
  interrupter.checkpoint(0.0);

  const BonePlacement placement =
      place_on_bones(avatar, source_skeleton, target_skeleton, skin_weights);
  const Skeleton source{source_skeleton.joints, target_skeleton.bones};
  CrossingCollapse collapse(avatar, source, placement);

  ShrinkResult result;
  TriangleMesh shrunk{MatrixX3d(avatar.vertices.rows(), 3), avatar.faces};
  const int checks_per_pullback = options.max_collapse_rounds + 1;
  const int total_checks = (options.max_halvings + 1) * checks_per_pullback;
  double pullback = options.pullback;
  std::optional<ShrinkConflict> conflict;
  for (int attempt = 0; attempt <= options.max_halvings; ++attempt, pullback *= 0.5) {
    shrunk.vertices = placement.on_bone + pullback * placement.offset;
    collapse.reset();
    for (int round = 0;; ++round) {
      ++result.certifications;
      conflict = find_shrink_conflict(shrunk, garment);
      interrupter.checkpoint(static_cast<double>(attempt * checks_per_pullback + round + 1) /
                             total_checks);
      if (!conflict) {
        result.vertices = shrunk.vertices;
        result.pullback = pullback;
        result.collapsed_vertices = collapse.collapsed_count();
        result.collapse_rounds = round;
        result.seconds = stopwatch.seconds();
        interrupter.checkpoint(1.0);
        return result;
      }
      if (conflict->kind != ShrinkConflict::Kind::kSurfacesCross ||
          round == options.max_collapse_rounds)
        break;
      collapse.apply(find_intersecting_face_pairs(shrunk, garment), options.collapse_step,
                     shrunk.vertices);
    }
  }
  throw NoValidShrinkError(
      fmt::format("no shrunk avatar is free of the garment: on the source skeleton with "
                  "pullback {:.3g}, after pulling crossing faces toward their joints, {}",
                  pullback * 2.0, conflict->describe()),
      *conflict, shrunk.vertices);
}

}  // namespace gr
