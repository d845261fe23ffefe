#include "core/skeleton/loop_bones.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "core/common/errors.hpp"

namespace gr {
namespace {

/// A loop is measured along a bone it goes round: seen along the bone, it turns about the
/// bone's line at least this many turns...
constexpr double kAroundTurns = 0.5;
/// ... and its centre lies along the bone within this share of the bone's length past
/// either end. Measured along a bone it does not go round (an eyelet on a shoe along a
/// finger), a loop would swing with the bone's turn times its distance.
constexpr double kBeyondBoneEnds = 0.5;

/// Whether `loop` (vertex ids of `garment`, centre `centre`) goes round the bone a → b.
bool goes_round(const Eigen::Ref<const MatrixX3d>& garment, const std::vector<int>& loop,
                const Vector3d& centre, const Vector3d& a, const Vector3d& b) {
  const double length = (b - a).norm();
  const Vector3d axis = (b - a) / length;
  const double along = (centre - a).dot(axis) / length;
  if (along < -kBeyondBoneEnds || along > 1.0 + kBeyondBoneEnds) return false;
  const auto across = [&](int v) {
    const Vector3d p = garment.row(v).transpose() - a;
    return Vector3d(p - p.dot(axis) * axis);
  };
  double turned = 0.0;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Vector3d p = across(loop[i]);
    const Vector3d q = across(loop[(i + 1) % loop.size()]);
    turned += std::atan2(axis.dot(p.cross(q)), p.dot(q));
  }
  return std::abs(turned) >= kAroundTurns * 2.0 * M_PI;
}

double point_segment_distance(const Vector3d& p, const Vector3d& a, const Vector3d& b) {
  const Vector3d d = b - a;
  const double length_sq = d.squaredNorm();
  const double s = length_sq > 0.0 ? std::clamp((p - a).dot(d) / length_sq, 0.0, 1.0) : 0.0;
  return (p - (a + s * d)).norm();
}

Vector3d joint(const Eigen::Ref<const MatrixX3d>& joints, int j) {
  return joints.row(j).transpose();
}

}  // namespace

LegJoints find_leg_joints(const Eigen::Ref<const MatrixX2i>& bones, int joint_count,
                          const std::string& skeleton_name) {
  std::vector<std::vector<int>> neighbours(static_cast<std::size_t>(joint_count));
  for (int b = 0; b < bones.rows(); ++b) {
    neighbours[bones(b, 0)].push_back(bones(b, 1));
    neighbours[bones(b, 1)].push_back(bones(b, 0));
  }
  // Leaf chains, listed from the branching joint outwards, grouped by branching joint.
  std::map<int, std::vector<std::vector<int>>> chains;
  for (int leaf = 0; leaf < joint_count; ++leaf) {
    if (neighbours[leaf].size() != 1) continue;
    std::vector<int> chain = {leaf};
    int previous = leaf, current = neighbours[leaf][0];
    while (neighbours[current].size() == 2) {
      chain.push_back(current);
      const int next =
          neighbours[current][0] == previous ? neighbours[current][1] : neighbours[current][0];
      previous = current;
      current = next;
    }
    if (neighbours[current].size() < 3) continue;  // a bare chain: no branching joint
    chains[current].emplace_back(chain.rbegin(), chain.rend());
  }
  const std::vector<int>* best[2] = {nullptr, nullptr};
  std::size_t best_size = 0;
  for (const auto& [branch, list] : chains) {
    if (list.size() != 2 || list[0].size() < 2 || list[1].size() < 2) continue;
    if (list[0].size() + list[1].size() > best_size) {
      best_size = list[0].size() + list[1].size();
      best[0] = &list[0];
      best[1] = &list[1];
    }
  }
  if (!best[0])
    throw InputError(skeleton_name, 0,
                     "no legs found for the skirt's virtual bone: no joint has exactly two "
                     "hanging chains of two or more joints");
  return LegJoints{{(*best[0])[0], (*best[1])[0]}, {(*best[0])[1], (*best[1])[1]}};
}

std::vector<LoopBone> assign_loop_bones(const Eigen::Ref<const MatrixX3d>& garment,
                                        const std::vector<std::vector<int>>& loops,
                                        const Eigen::Ref<const MatrixX3d>& source_joints,
                                        const Eigen::Ref<const MatrixX3d>& target_joints,
                                        const Eigen::Ref<const MatrixX2i>& bones,
                                        const std::vector<char>& skirt_vertices) {
  std::vector<LoopBone> result;
  const auto is_skirt = [&](const std::vector<int>& loop) {
    return !skirt_vertices.empty() && skirt_vertices[static_cast<std::size_t>(loop.front())];
  };
  MovingBone virtual_bone;
  if (std::any_of(loops.begin(), loops.end(),
                  [&](const auto& loop) { return loop.size() >= 3 && is_skirt(loop); })) {
    const LegJoints legs =
        find_leg_joints(bones, static_cast<int>(source_joints.rows()), "source skeleton");
    const auto midpoint = [](const Eigen::Ref<const MatrixX3d>& joints, const int pair[2]) {
      return Vector3d(0.5 * (joint(joints, pair[0]) + joint(joints, pair[1])));
    };
    virtual_bone = {midpoint(source_joints, legs.hips), midpoint(source_joints, legs.knees),
                    midpoint(target_joints, legs.hips), midpoint(target_joints, legs.knees)};
  }
  const double min_cosine = std::cos(60.0 * M_PI / 180.0);
  for (const auto& loop : loops) {
    if (loop.size() < 3) continue;
    Vector3d centre = Vector3d::Zero(), normal = Vector3d::Zero();
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const Vector3d p = garment.row(loop[i]).transpose();
      const Vector3d q = garment.row(loop[(i + 1) % loop.size()]).transpose();
      centre += p;
      normal += p.cross(q);
    }
    centre /= static_cast<double>(loop.size());
    if (is_skirt(loop)) {
      result.push_back({loop, virtual_bone, -1});
      continue;
    }
    if (!(normal.norm() > 0.0)) continue;
    normal.normalize();
    int best = -1;
    double best_distance = std::numeric_limits<double>::infinity();
    for (int b = 0; b < bones.rows(); ++b) {
      const Vector3d a = joint(source_joints, bones(b, 0));
      const Vector3d c = joint(source_joints, bones(b, 1));
      const Vector3d direction = c - a;
      if (!(direction.norm() > 0.0)) continue;
      if (std::abs(direction.normalized().dot(normal)) < min_cosine) continue;
      if (!goes_round(garment, loop, centre, a, c)) continue;
      const double distance = point_segment_distance(centre, a, c);
      if (distance < best_distance) {
        best_distance = distance;
        best = b;
      }
    }
    if (best < 0) continue;
    const MovingBone bone{
        joint(source_joints, bones(best, 0)), joint(source_joints, bones(best, 1)),
        joint(target_joints, bones(best, 0)), joint(target_joints, bones(best, 1))};
    result.push_back({loop, bone, best});
  }
  return result;
}

}  // namespace gr
