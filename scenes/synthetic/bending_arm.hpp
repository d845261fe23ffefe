#pragma once

#include <string>

#include "core/io/gltf_animation.hpp"
#include "core/io/gltf_document.hpp"

namespace gr {

/// A sleeve on an arm that bends at the elbow: the smallest scene in which playing a garment
/// by its skin lets it cross the avatar. The arm (a closed tube along +x, from the shoulder
/// at the origin through the elbow at x = 1 to the wrist at x = 2) blends its two bones over
/// a band around the elbow; the sleeve, a looser open tube over the middle of the arm, is
/// skinned rigidly to one bone or the other, as a garment whose weights came from another
/// body can be. The clip turns the elbow about +z.
struct BendingArmScene {
  ObjDocument arm;
  ObjDocument sleeve;
  SkinBinding arm_skin;     ///< joints shoulder, elbow, wrist
  SkinBinding sleeve_skin;  ///< the same joints, the sleeve's weights
  AnimationClip bend;       ///< "bend": the elbow from straight to `bend_degrees` in 1 s
};

/// The scene, with the elbow turning by `bend_degrees` (positive: toward +y).
BendingArmScene make_bending_arm_scene(double bend_degrees = 90.0);

/// The scene as files in `folder`: `arm.glb` (the arm, skinned, with the clip), `sleeve.glb`
/// (the sleeve, skinned over the same joints, no clip) and `clip.glb` (the clip alone, over
/// a small stand-in mesh skinned to the same joint names: a clip from another file).
void write_bending_arm_scene(const BendingArmScene& scene, const std::string& folder);

}  // namespace gr
