#pragma once

#include <Eigen/Geometry>

#include "core/inflation/garment_problem.hpp"
#include "core/test_shapes.hpp"

namespace gr::test {

/// A sphere avatar of radius 1 (icosphere), shrunk to A0 = 0.5 A about its centre, inside a
/// closed sphere garment of radius 0.9 (a coarser icosphere, turned so no vertex lines up).
inline GarmentScene inflating_sphere_scene(int avatar_subdivisions = 2,
                                           int garment_subdivisions = 2) {
  GarmentScene scene;
  scene.avatar = icosphere(avatar_subdivisions, 1.0);
  scene.shrunk_avatar = 0.5 * scene.avatar.vertices;
  scene.garment = icosphere(garment_subdivisions, 0.9);
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(0.3, Vector3d(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
  scene.garment.vertices = (scene.garment.vertices * turn.transpose()).eval();
  return scene;
}

}  // namespace gr::test
