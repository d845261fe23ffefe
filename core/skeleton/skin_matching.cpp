#include "core/skeleton/skin_matching.hpp"

#include <algorithm>
#include <array>
#include <deque>
#include <limits>
#include <map>
#include <sstream>

#include <fmt/format.h>

#include "core/common/errors.hpp"
#include "core/io/text_file.hpp"

namespace gr {

JointMap read_joint_map(const std::string& path) {
  const TextFile file(path);
  JointMap map;
  std::map<std::string, std::size_t> seen;
  for (std::size_t index = 0; index < file.line_count(); ++index) {
    const std::size_t line = index + 1;
    std::string text(file.line(index));
    if (const auto hash = text.find('#'); hash != std::string::npos) text.erase(hash);
    std::istringstream words(text);
    std::vector<std::string> names;
    for (std::string word; words >> word;) names.push_back(word);
    if (names.empty()) continue;
    if (names.size() != 2) throw InputError(path, line, "expected `source_joint target_joint`");
    if (!seen.emplace(names[0], line).second)
      throw InputError(path, line, fmt::format("joint '{}' is mapped twice", names[0]));
    map.emplace_back(names[0], names[1]);
  }
  return map;
}

MatchedSkeletons match_skin_skeletons(const SkinBinding& source, const SkinBinding& target,
                                      const JointMap& map, const std::string& target_path) {
  std::map<std::string, int> target_by_name;
  for (std::size_t j = 0; j < target.joints.size(); ++j)
    target_by_name.emplace(target.joints[j].name, static_cast<int>(j));
  std::map<std::string, std::string> renamed(map.begin(), map.end());

  MatchedSkeletons matched;
  std::vector<int> kept_of_source(source.joints.size(), -1);
  std::vector<std::string> missing;
  for (std::size_t j = 0; j < source.joints.size(); ++j) {
    std::string name = source.joints[j].name;
    if (const auto it = renamed.find(name); it != renamed.end()) name = it->second;
    if (name == "-") continue;
    const auto it = target_by_name.find(name);
    if (it == target_by_name.end()) {
      missing.push_back(source.joints[j].name);
      continue;
    }
    kept_of_source[j] = static_cast<int>(matched.target_joint.size());
    matched.target_joint.push_back(it->second);
  }
  if (!missing.empty())
    throw InputError(target_path, 0,
                     fmt::format("the avatar's skin lacks {} of the garment's skin joints: '{}' "
                                 "(map them with --joint-map, or to '-' to leave them out)",
                                 missing.size(), fmt::join(missing, "', '")));
  const auto kept = static_cast<Eigen::Index>(matched.target_joint.size());
  if (kept < 2) throw InputError(target_path, 0, "fewer than two skin joints match");

  matched.source.joints.resize(kept, 3);
  matched.target.joints.resize(kept, 3);
  std::vector<std::array<int, 2>> bones;
  for (std::size_t j = 0; j < source.joints.size(); ++j) {
    const int k = kept_of_source[j];
    if (k < 0) continue;
    matched.source.joints.row(k) = source.joints[j].world.topRightCorner<3, 1>().transpose();
    matched.target.joints.row(k) =
        target.joints[static_cast<std::size_t>(matched.target_joint[static_cast<std::size_t>(k)])]
            .world.topRightCorner<3, 1>()
            .transpose();
    for (int p = source.joints[j].parent; p >= 0;
         p = source.joints[static_cast<std::size_t>(p)].parent)
      if (kept_of_source[static_cast<std::size_t>(p)] >= 0) {
        bones.push_back({kept_of_source[static_cast<std::size_t>(p)], k});
        break;
      }
  }
  if (bones.empty()) throw InputError(target_path, 0, "the matched skin joints form no bone");
  matched.source.bones.resize(static_cast<Eigen::Index>(bones.size()), 2);
  for (std::size_t b = 0; b < bones.size(); ++b)
    matched.source.bones.row(static_cast<Eigen::Index>(b)) << bones[b][0], bones[b][1];
  matched.target.bones = matched.source.bones;

  std::vector<int> kept_of_target(target.joints.size(), -1);
  for (std::size_t k = 0; k < matched.target_joint.size(); ++k)
    kept_of_target[static_cast<std::size_t>(matched.target_joint[k])] = static_cast<int>(k);
  for (std::size_t j = 0; j < target.joints.size(); ++j) {
    int to = 0;
    for (int a = static_cast<int>(j); a >= 0; a = target.joints[static_cast<std::size_t>(a)].parent)
      if (kept_of_target[static_cast<std::size_t>(a)] >= 0) {
        to = kept_of_target[static_cast<std::size_t>(a)];
        break;
      }
    matched.kept_joint_of_target.push_back(to);
  }
  return matched;
}

std::pair<Eigen::Index, double> nearest_bone(const Skeleton& skeleton, const Vector3d& point) {
  std::pair<Eigen::Index, double> nearest{0, 0.0};
  double best = std::numeric_limits<double>::infinity();
  for (Eigen::Index b = 0; b < skeleton.bones.rows(); ++b) {
    const Vector3d a = skeleton.joints.row(skeleton.bones(b, 0)).transpose();
    const Vector3d d = skeleton.joints.row(skeleton.bones(b, 1)).transpose() - a;
    const double s =
        d.squaredNorm() > 0.0 ? std::clamp((point - a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
    const double distance_sq = (a + s * d - point).squaredNorm();
    if (distance_sq >= best) continue;
    best = distance_sq;
    nearest = {b, s};
  }
  return nearest;
}

Eigen::MatrixXd nearest_bone_weights(const Skeleton& skeleton,
                                     const Eigen::Ref<const MatrixX3d>& points) {
  Eigen::MatrixXd weights = Eigen::MatrixXd::Zero(skeleton.joints.rows(), points.rows());
  for (Eigen::Index v = 0; v < points.rows(); ++v) {
    const auto [bone, s] = nearest_bone(skeleton, points.row(v).transpose());
    weights(skeleton.bones(bone, 0), v) += 1.0 - s;
    weights(skeleton.bones(bone, 1), v) += s;
  }
  return weights;
}

SkinBinding skin_of_skeleton(const Skeleton& skeleton, const Eigen::MatrixXd& weights) {
  const auto count = static_cast<std::size_t>(skeleton.joints.rows());
  std::vector<std::vector<int>> neighbours(count);
  for (Eigen::Index b = 0; b < skeleton.bones.rows(); ++b) {
    neighbours[static_cast<std::size_t>(skeleton.bones(b, 0))].push_back(skeleton.bones(b, 1));
    neighbours[static_cast<std::size_t>(skeleton.bones(b, 1))].push_back(skeleton.bones(b, 0));
  }
  SkinBinding skin;
  skin.joints.resize(count);
  std::vector<bool> seen(count, false);
  for (std::size_t root = 0; root < count; ++root) {
    if (seen[root]) continue;
    seen[root] = true;
    std::deque<int> queue{static_cast<int>(root)};
    while (!queue.empty()) {
      const int joint = queue.front();
      queue.pop_front();
      for (const int next : neighbours[static_cast<std::size_t>(joint)])
        if (!seen[static_cast<std::size_t>(next)]) {
          seen[static_cast<std::size_t>(next)] = true;
          skin.joints[static_cast<std::size_t>(next)].parent = joint;
          queue.push_back(next);
        }
    }
  }
  for (std::size_t j = 0; j < count; ++j) {
    SkinJoint& joint = skin.joints[j];
    joint.name = fmt::format("joint_{}", j);
    joint.world.setIdentity();
    joint.world.topRightCorner<3, 1>() =
        skeleton.joints.row(static_cast<Eigen::Index>(j)).transpose();
    joint.inverse_bind = joint.world.inverse();
  }
  for (SkinJoint& joint : skin.joints)
    joint.translation =
        joint.world.topRightCorner<3, 1>() -
        (joint.parent >= 0
             ? Eigen::Vector3d(
                   skin.joints[static_cast<std::size_t>(joint.parent)].world.topRightCorner<3, 1>())
             : Eigen::Vector3d::Zero());
  skin.weights = weights;
  return skin;
}

}  // namespace gr
