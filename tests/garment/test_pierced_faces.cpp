#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/mesh/primitives.hpp"
#include "garment/repairs/pierced_faces.hpp"

using namespace gr;

namespace {

/// One bone along y from -3 to 3, through the cube's bottom and top.
Skeleton vertical_bone() {
  Skeleton skeleton;
  skeleton.joints.resize(2, 3);
  skeleton.joints << 0.1, -3, 0.2, 0.1, 3, 0.2;
  skeleton.bones.resize(1, 2);
  skeleton.bones << 0, 1;
  return skeleton;
}

}  // namespace

TEST_CASE("Bones through a closed shell name its pierced faces", "[pierced]") {
  const TriangleMesh cube = box(Vector3d::Ones());  // side 2, 12 faces, outward
  const Skeleton bone = vertical_bone();
  const std::vector<FacePair> pierced = faces_pierced_by_bones(cube, bone);
  REQUIRE(pierced.size() == 2);  // one face of the bottom, one of the top
  for (const FacePair& p : pierced) CHECK(p.second == 0);
  // Open at top and bottom (a tube: without the y = -1 and y = 1 faces, rows 4 to 7),
  // nothing is pierced.
  TriangleMesh tube = cube;
  tube.faces.resize(8, 3);
  tube.faces << cube.faces.topRows(4), cube.faces.bottomRows(4);
  CHECK(faces_pierced_by_bones(tube, bone).empty());
  std::vector<int> face_to_obj(12);
  for (int f = 0; f < 12; ++f) face_to_obj[static_cast<std::size_t>(f)] = f;
  const std::string line = describe_pierced_faces(pierced, face_to_obj, bone, {"Hips", "Head"});
  CHECK_THAT(line, Catch::Contains("2 garment faces") && Catch::Contains("Hips-Head") &&
                       Catch::Contains("closed shell or cap"));
}
