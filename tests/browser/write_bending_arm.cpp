// Writes the synthetic bending-arm scene (scenes/synthetic/bending_arm.hpp) into a folder:
// arm.glb with its clip "bend", sleeve.glb and clip.glb, the browser tests' skinned scene.
//
//   write_bending_arm OUT_DIR [BEND_DEGREES]
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include "scenes/synthetic/bending_arm.hpp"

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::fprintf(stderr, "usage: write_bending_arm OUT_DIR [BEND_DEGREES]\n");
    return 2;
  }
  try {
    std::filesystem::create_directories(argv[1]);
    const double degrees = argc == 3 ? std::stod(argv[2]) : 90.0;
    gr::write_bending_arm_scene(gr::make_bending_arm_scene(degrees), argv[1]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "write_bending_arm: %s\n", e.what());
    return 1;
  }
  return 0;
}
