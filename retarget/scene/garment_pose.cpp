#include "retarget/scene/garment_pose.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include <fmt/format.h>

#include "garment/repairs/untangle.hpp"
#include "validate/checks/self_intersections.hpp"
#include "validate/measure/shape_change.hpp"

namespace gr {

const char* to_string(PoseMode mode) { return mode == PoseMode::kTarget ? "target" : "as-given"; }

PoseMode parse_pose_mode(const std::string& name) {
  if (name == "target") return PoseMode::kTarget;
  if (name == "as-given") return PoseMode::kAsGiven;
  throw std::invalid_argument("pose mode must be target or as-given, not '" + name + "'");
}

nlohmann::json to_json(const PoseReport& report) {
  return {{"mode", to_string(report.mode)},
          {"posed", report.posed},
          {"reason", report.reason},
          {"untangled_pairs", report.untangled_pairs},
          {"skinning", to_string(report.method)},
          {"joints", report.joints},
          {"largest_turn_degrees", report.largest_turn_degrees},
          {"edge_change", {{"mean", report.mean_edge_change}, {"p95", report.p95_edge_change}}},
          {"source_body_posed", report.source_body_posed}};
}

namespace {

/// The self-intersecting face pairs of `mesh`, each (smaller face, larger face), sorted.
std::vector<FacePair> sorted_self_pairs(const TriangleMesh& mesh) {
  std::vector<FacePair> pairs = find_self_intersecting_face_pairs(mesh).pairs.pairs;
  for (FacePair& p : pairs) p = {std::min(p.first, p.second), std::max(p.first, p.second)};
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

/// Self-intersecting face pairs of `after` that are not among `had` (sorted_self_pairs of
/// the same faces before), sorted.
std::vector<FacePair> added_crossings(const std::vector<FacePair>& had, const TriangleMesh& after) {
  std::vector<FacePair> added;
  for (const FacePair& p : sorted_self_pairs(after))
    if (!std::binary_search(had.begin(), had.end(), p)) added.push_back(p);
  return added;
}

/// The pose step's untangle, as fractions of the avatar's largest side: the gap a push
/// leaves (the solve's barrier support is 0.1 % of it), and the furthest a vertex may move
/// (2.5 %: cloth a bend folds, as at an armpit, goes further than crossings as given).
constexpr double kPoseUntangleSeparation = 5e-4;
constexpr double kPoseUntangleBudget = 2.5e-2;

/// The largest turn of a joint in one step of the pose step (10 degrees).
constexpr double kPoseStepRadians = 10.0 * M_PI / 180.0;

/// The share `s` in [0, 1] of each joint's motion: its turn slerped about the joint, the
/// joint itself moved in a straight line (s = 1 gives the motions themselves).
std::vector<Eigen::Isometry3d> partial_motions(const Skeleton& source,
                                               const std::vector<Eigen::Isometry3d>& motions,
                                               double s) {
  std::vector<Eigen::Isometry3d> partial;
  for (std::size_t j = 0; j < motions.size(); ++j) {
    const Vector3d joint = source.joints.row(static_cast<Eigen::Index>(j)).transpose();
    const Eigen::Quaterniond turn =
        Eigen::Quaterniond::Identity().slerp(s, Eigen::Quaterniond(motions[j].linear()));
    Eigen::Isometry3d m = Eigen::Isometry3d::Identity();
    m.linear() = turn.toRotationMatrix();
    m.translation() = joint + s * (motions[j] * joint - joint) - m.linear() * joint;
    partial.push_back(m);
  }
  return partial;
}

/// The crossings `made` by the turn pushed apart on `posed` (untangle_crossings; the
/// input's own are left to the prepare stage). Returns the pairs still crossing that
/// are not among `had` (the input's own, sorted_self_pairs), and in `why` how many of them
/// the untangle left for each reason.
std::vector<FacePair> untangle_pose_crossings(const std::vector<FacePair>& had, TriangleMesh& posed,
                                              const std::vector<FacePair>& made, double avatar_side,
                                              std::string& why) {
  UntangleOptions options;
  options.separation = kPoseUntangleSeparation * avatar_side;
  options.max_displacement = kPoseUntangleBudget * avatar_side;
  Untangled untangled = untangle_crossings(posed, made, options);
  posed.vertices = std::move(untangled.vertices);
  std::vector<FacePair> left = added_crossings(had, posed);
  std::map<std::string, int> reasons;
  for (const LeftCrossing& crossing : untangled.left) {
    const FacePair p{std::min(crossing.pair.first, crossing.pair.second),
                     std::max(crossing.pair.first, crossing.pair.second)};
    if (std::binary_search(left.begin(), left.end(), p)) ++reasons[to_string(crossing.reason)];
  }
  why.clear();
  for (const auto& [reason, count] : reasons)
    why += fmt::format("{}{} {}", why.empty() ? "" : ", ", count, reason);
  return left;
}
}  // namespace

PoseReport pose_garment(Scene& scene, PoseMode mode, SkinningMethod method) {
  PoseReport report;
  report.mode = mode;
  report.method = method;
  if (mode == PoseMode::kAsGiven) {
    report.reason = "--pose as-given";
    return report;
  }
  const bool skinned = scene.garment_gltf && scene.garment_gltf->skin &&
                       scene.garment_gltf->skin->weights.cols() > 0;
  if (scene.joint_names.empty() || !skinned) {
    report.reason = "the garment and the avatar do not both have a glTF skin";
    return report;
  }
  if (scene.layers.size() > 1) {
    report.reason = "an outfit keeps its pose";
    return report;
  }
  const SkinBinding& skin = *scene.garment_gltf->skin;
  const Skeleton& source = *scene.source_skeleton;
  if (static_cast<Eigen::Index>(skin.joints.size()) != source.joints.rows()) {
    report.reason = "the joint map leaves joints of the garment's skin out";
    return report;
  }
  const std::vector<Eigen::Isometry3d> motions =
      pose_transfer_motions(source, *scene.target_skeleton);
  ObjDocument& document = scene.garment_document;
  const TriangleMesh before = scene.garment.mesh;
  const double avatar_side = (scene.avatar.mesh.vertices.colwise().maxCoeff() -
                              scene.avatar.mesh.vertices.colwise().minCoeff())
                                 .maxCoeff();
  // Joints that hold none of the garment (a hand's fingers under a sleeve) turn none of it.
  double largest_turn = 0.0;
  for (std::size_t j = 0; j < motions.size(); ++j)
    if (skin.weights.row(static_cast<Eigen::Index>(j)).maxCoeff() > 0.0)
      largest_turn = std::max(largest_turn, Eigen::AngleAxisd(motions[j].linear()).angle());
  // A skin whose weights fold the cloth onto itself (an arm lowered through the armpit's
  // cloth) makes crossings the input did not have; were any left, they would pass for the
  // input's own in the solve, so they are pushed apart, or the pose is kept. The turn is
  // tried in one step, then in steps of kPoseStepRadians, what each step makes (still
  // shallow) pushed apart before the next.
  const auto sim_rows = [&](const MatrixX3d& document_rows) {
    MatrixX3d rows(before.vertices.rows(), 3);
    for (std::size_t v = 0; v < scene.garment.sim_to_obj.size(); ++v)
      rows.row(static_cast<Eigen::Index>(v)) = document_rows.row(scene.garment.sim_to_obj[v]);
    return rows;
  };
  const std::vector<FacePair> had = sorted_self_pairs(before);
  TriangleMesh after = before;
  MatrixX3d posed;
  std::size_t made = 0;
  std::string why;
  std::size_t left = 0;
  for (const int steps :
       {1, std::max(2, static_cast<int>(std::ceil(largest_turn / kPoseStepRadians)))}) {
    after = before;
    MatrixX3d skinned_before = before.vertices;
    made = left = 0;
    for (int step = 1; step <= steps && left == 0; ++step) {
      posed = skin_by_motions(document.positions, skin.weights,
                              partial_motions(source, motions, double(step) / steps), method);
      const MatrixX3d skinned = sim_rows(posed);
      after.vertices += skinned - skinned_before;
      skinned_before = skinned;
      const std::vector<FacePair> added = added_crossings(had, after);
      made += added.size();
      if (added.empty()) continue;
      left = untangle_pose_crossings(had, after, added, avatar_side, why).size();
    }
    if (left == 0) break;
  }
  if (left > 0) {
    report.reason = fmt::format(
        "turned by its skin, the garment would cross itself in {} face pairs it did not "
        "before, {} of them left after untangling ({})",
        made, left, why);
    return report;
  }
  report.untangled_pairs = static_cast<int>(made);
  document.positions = posed;
  for (std::size_t i = 0; i < scene.garment.obj_to_sim.size(); ++i)
    if (const int s = scene.garment.obj_to_sim[i]; s >= 0)
      document.positions.row(static_cast<Eigen::Index>(i)) = after.vertices.row(s);
  scene.garment.mesh.vertices = after.vertices;
  scene.layers.front().document.positions = document.positions;
  scene.source_skeleton->joints = moved_joints(source, motions);
  scene.garment_pose = GarmentPose{{}, motions, method};
  for (const SkinJoint& joint : skin.joints) scene.garment_pose->joint_names.push_back(joint.name);

  report.posed = true;
  report.joints = static_cast<int>(motions.size());
  report.largest_turn_degrees = largest_turn * 180.0 / M_PI;
  const ShapeChange change = measure_shape_change(before, scene.garment.mesh.vertices);
  report.mean_edge_change = change.mean_edge_change;
  report.p95_edge_change = change.p95_edge_change;
  return report;
}

bool pose_like_garment(const Scene& scene, const SkinBinding& skin, MatrixX3d& positions) {
  if (!scene.garment_pose || skin.weights.cols() != positions.rows() ||
      skin.joints.size() != scene.garment_pose->joint_names.size())
    return false;
  for (std::size_t j = 0; j < skin.joints.size(); ++j)
    if (skin.joints[j].name != scene.garment_pose->joint_names[j]) return false;
  positions = skin_by_motions(positions, skin.weights, scene.garment_pose->motions,
                              scene.garment_pose->method);
  return true;
}

}  // namespace gr
