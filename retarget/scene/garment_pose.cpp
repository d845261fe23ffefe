#include "retarget/scene/garment_pose.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

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
          {"skinning", to_string(report.method)},
          {"joints", report.joints},
          {"largest_turn_degrees", report.largest_turn_degrees},
          {"edge_change", {{"mean", report.mean_edge_change}, {"p95", report.p95_edge_change}}},
          {"source_body_posed", report.source_body_posed}};
}

namespace {

/// Self-intersecting face pairs of `after` that `before` (same faces) does not have.
std::size_t added_crossings(const TriangleMesh& before, const TriangleMesh& after) {
  std::vector<FacePair> had = find_self_intersecting_face_pairs(before).pairs.pairs;
  for (FacePair& p : had) p = {std::min(p.first, p.second), std::max(p.first, p.second)};
  std::sort(had.begin(), had.end());
  std::size_t added = 0;
  for (FacePair p : find_self_intersecting_face_pairs(after).pairs.pairs) {
    p = {std::min(p.first, p.second), std::max(p.first, p.second)};
    if (!std::binary_search(had.begin(), had.end(), p)) ++added;
  }
  return added;
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
  const MatrixX3d posed = skin_by_motions(document.positions, skin.weights, motions, method);
  // A skin whose weights fold the cloth onto itself would hand the solve crossings that the
  // input did not have, and that would then pass for the input's own: keep the pose.
  TriangleMesh after = before;
  for (std::size_t s = 0; s < scene.garment.sim_to_obj.size(); ++s)
    after.vertices.row(static_cast<Eigen::Index>(s)) = posed.row(scene.garment.sim_to_obj[s]);
  const std::size_t added = added_crossings(before, after);
  if (added > 0) {
    report.reason = fmt::format(
        "turned by its skin, the garment would cross itself in {} more face pairs", added);
    return report;
  }
  document.positions = posed;
  for (std::size_t s = 0; s < scene.garment.sim_to_obj.size(); ++s)
    scene.garment.mesh.vertices.row(static_cast<Eigen::Index>(s)) =
        document.positions.row(scene.garment.sim_to_obj[s]);
  scene.layers.front().document.positions = document.positions;
  scene.source_skeleton->joints = moved_joints(source, motions);
  scene.garment_pose = GarmentPose{{}, motions, method};
  for (const SkinJoint& joint : skin.joints) scene.garment_pose->joint_names.push_back(joint.name);

  report.posed = true;
  report.joints = static_cast<int>(motions.size());
  for (const Eigen::Isometry3d& m : motions)
    report.largest_turn_degrees =
        std::max(report.largest_turn_degrees, Eigen::AngleAxisd(m.linear()).angle() * 180.0 / M_PI);
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
