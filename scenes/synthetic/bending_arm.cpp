#include "scenes/synthetic/bending_arm.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace gr {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// A tube along +x from x0 to x1: `rings` rings of `sides` vertices; closed by two fans
/// when `capped`. Outward faces.
ObjDocument tube(double x0, double x1, double radius, int rings, int sides, bool capped) {
  ObjDocument document;
  const int ring_vertices = rings * sides;
  document.positions.resize(ring_vertices + (capped ? 2 : 0), 3);
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < sides; ++s) {
      const double x = x0 + (x1 - x0) * r / (rings - 1);
      const double a = 2.0 * kPi * s / sides;
      document.positions.row(r * sides + s) << x, radius * std::cos(a), radius * std::sin(a);
    }
  const auto corner = [](int v) { return ObjCorner{v, -1, -1}; };
  for (int r = 0; r + 1 < rings; ++r)
    for (int s = 0; s < sides; ++s) {
      const int a = r * sides + s;
      const int b = r * sides + (s + 1) % sides;
      const int c = a + sides;
      const int d = b + sides;
      document.faces.push_back({corner(a), corner(b), corner(d)});
      document.faces.push_back({corner(a), corner(d), corner(c)});
    }
  if (capped) {
    const int start = ring_vertices;
    const int end = ring_vertices + 1;
    document.positions.row(start) << x0, 0.0, 0.0;
    document.positions.row(end) << x1, 0.0, 0.0;
    const int last = (rings - 1) * sides;
    for (int s = 0; s < sides; ++s) {
      const int t = (s + 1) % sides;
      document.faces.push_back({corner(start), corner(t), corner(s)});
      document.faces.push_back({corner(end), corner(last + s), corner(last + t)});
    }
  }
  return document;
}

/// Shoulder, elbow and wrist on +x, each a child of the one before.
SkinBinding arm_joints() {
  SkinBinding skin;
  const char* names[] = {"shoulder", "elbow", "wrist"};
  for (int j = 0; j < 3; ++j) {
    SkinJoint joint;
    joint.name = names[j];
    joint.parent = j - 1;
    joint.world.setIdentity();
    joint.world(0, 3) = j;
    joint.inverse_bind = joint.world.inverse();
    joint.translation = Eigen::Vector3d(j == 0 ? 0.0 : 1.0, 0.0, 0.0);
    skin.joints.push_back(joint);
  }
  return skin;
}

/// Weights over shoulder and elbow: the elbow's share rises from 0 to 1 across
/// [1 - band, 1 + band] (smoothly), or steps at x = 1 when band is 0.
Eigen::MatrixXd elbow_weights(const MatrixX3d& positions, double band) {
  Eigen::MatrixXd weights = Eigen::MatrixXd::Zero(3, positions.rows());
  for (Eigen::Index v = 0; v < positions.rows(); ++v) {
    const double x = positions(v, 0);
    double elbow = x >= 1.0 ? 1.0 : 0.0;
    if (band > 0.0) {
      const double s = std::clamp((x - (1.0 - band)) / (2.0 * band), 0.0, 1.0);
      elbow = s * s * (3.0 - 2.0 * s);
    }
    weights(0, v) = 1.0 - elbow;
    weights(1, v) = elbow;
  }
  return weights;
}

}  // namespace

BendingArmScene make_bending_arm_scene(double bend_degrees) {
  BendingArmScene scene;
  scene.arm = tube(0.0, 2.0, 0.3, 41, 24, true);
  scene.sleeve = tube(0.2, 1.8, 0.34, 33, 24, false);
  scene.arm_skin = arm_joints();
  scene.arm_skin.weights = elbow_weights(scene.arm.positions, 0.15);
  scene.sleeve_skin = arm_joints();
  scene.sleeve_skin.weights = elbow_weights(scene.sleeve.positions, 0.0);
  scene.bend.name = "bend";
  AnimationChannel elbow;
  elbow.node = "elbow";
  elbow.path = ChannelPath::kRotation;
  elbow.interpolation = KeyInterpolation::kLinear;
  elbow.times = {0.0, 0.5, 1.0};
  elbow.values.resize(3, 4);
  for (int k = 0; k < 3; ++k) {
    const double half = 0.5 * bend_degrees * kPi / 180.0 * elbow.times[static_cast<std::size_t>(k)];
    elbow.values.row(k) << 0.0, 0.0, std::sin(half), std::cos(half);
  }
  scene.bend.channels.push_back(elbow);
  scene.bend.start = 0.0;
  scene.bend.end = 1.0;
  return scene;
}

void write_bending_arm_scene(const BendingArmScene& scene, const std::string& folder) {
  std::filesystem::create_directories(folder);
  const std::filesystem::path dir(folder);
  write_glb_meshes((dir / "arm.glb").string(),
                   {GlbMesh{"arm", &scene.arm, nullptr, scene.arm.positions, &scene.arm_skin}},
                   {scene.bend});
  write_glb_meshes(
      (dir / "sleeve.glb").string(),
      {GlbMesh{"sleeve", &scene.sleeve, nullptr, scene.sleeve.positions, &scene.sleeve_skin}});
  ObjDocument stand_in = tube(0.0, 2.0, 0.05, 2, 3, false);
  SkinBinding stand_in_skin = arm_joints();
  stand_in_skin.weights = elbow_weights(stand_in.positions, 0.0);
  write_glb_meshes((dir / "clip.glb").string(),
                   {GlbMesh{"stand_in", &stand_in, nullptr, stand_in.positions, &stand_in_skin}},
                   {scene.bend});
}

}  // namespace gr
