#include <algorithm>
#include <stdexcept>
#include <vector>

#include <tbb/global_control.h>
#include <catch2/catch.hpp>

#include "core/mesh/primitives.hpp"
#include "garment/layers/hidden_faces.hpp"
#include "garment/outfit_meshes.hpp"

using namespace gr;
using gr::test::closed_cylinder;

namespace {

constexpr int kSegments = 32;
constexpr int kBands = 16;  // side bands of 0.25 between z = −2 and 2
constexpr int kSideFaces = 2 * kSegments * kBands;

/// The side faces of the capsule whose corners all lie at z >= z_min.
std::vector<int> side_faces_above(const TriangleMesh& capsule, double z_min) {
  std::vector<int> out;
  for (int f = 0; f < kSideFaces; ++f) {
    bool above = true;
    for (int k = 0; k < 3; ++k) above = above && capsule.vertices(capsule.faces(f, k), 2) >= z_min;
    if (above) out.push_back(f);
  }
  return out;
}

/// The band (0 at the bottom) of a side face of the capsule.
int band_of(int face) { return face / (2 * kSegments); }

}  // namespace

TEST_CASE("A sleeve over half a capsule hides the faces under it, away from its opening",
          "[outfit][hidden]") {
  // Capsule of radius 1 over z in [−2, 2]; the sleeve (radius 1.2) covers z in [0, 3], so
  // its lower opening lies at z = 0 and its upper one well above the capsule's top.
  const TriangleMesh capsule = closed_cylinder(1.0, -2.0, 2.0, kBands + 1, kSegments);
  REQUIRE(capsule.faces.rows() == kSideFaces + 2 * kSegments);
  const TriangleMesh sleeve = open_cylinder(1.2, 0.0, 3.0, 13, 48);
  HiddenFaceOptions options;
  options.margin = 0.5;

  const HiddenFaces hidden = faces_hidden_by_outfit(capsule, sleeve, options);
  CHECK(hidden.face_count == kSideFaces + 2 * kSegments);
  // The bands from z = 0.5 up: every ray of the cone meets the sleeve (the steepest one
  // down, 60° from the normal, drops about 0.35 on the way) and the opening is further
  // than 0.5 away (at least sqrt(0.2² + 0.5²)).
  const std::vector<int> expected = side_faces_above(capsule, 0.5 - 1e-12);
  REQUIRE(expected.size() == 6u * 2 * kSegments);
  CHECK(hidden.faces == expected);
  CHECK(hidden.hidden == static_cast<int>(expected.size()));
  CHECK(hidden.kept_degenerate == 0);
  CHECK(hidden.hidden + hidden.kept_escaping + hidden.kept_near_opening == hidden.face_count);
  // In the band z in [0.25, 0.5], the faces whose centroid lies at z = 5/12 see only the
  // sleeve, but their lower corners lie 0.32 from the opening.
  CHECK(hidden.kept_near_opening == kSegments);
  // Specific faces: the bottom half, the band at the opening, both caps.
  for (const int f : {0, 5 * 2 * kSegments + 7, 8 * 2 * kSegments + 3, 9 * 2 * kSegments + 1,
                      kSideFaces, kSideFaces + kSegments + 5}) {
    CAPTURE(f);
    CHECK_FALSE(std::binary_search(hidden.faces.begin(), hidden.faces.end(), f));
  }
  CHECK(std::binary_search(hidden.faces.begin(), hidden.faces.end(), 10 * 2 * kSegments));
  CHECK(std::binary_search(hidden.faces.begin(), hidden.faces.end(), kSideFaces - 1));

  SECTION("without the margin, the faces kept near the opening are hidden") {
    HiddenFaceOptions no_margin = options;
    no_margin.margin = 0.0;
    const HiddenFaces all = faces_hidden_by_outfit(capsule, sleeve, no_margin);
    CHECK(all.kept_near_opening == 0);
    CHECK(all.hidden == hidden.hidden + hidden.kept_near_opening);
    CHECK(std::includes(all.faces.begin(), all.faces.end(), hidden.faces.begin(),
                        hidden.faces.end()));
    for (const int f : all.faces)
      if (!std::binary_search(hidden.faces.begin(), hidden.faces.end(), f)) CHECK(band_of(f) == 9);
  }
  SECTION("the normal alone, with no margin, hides the whole covered half") {
    HiddenFaceOptions normal_only = options;
    normal_only.ring_rays = 0;
    normal_only.margin = 0.0;
    const HiddenFaces covered = faces_hidden_by_outfit(capsule, sleeve, normal_only);
    // Every side face of the upper half sends its normal into the sleeve.
    CHECK(covered.faces == side_faces_above(capsule, 0.0));
  }
  SECTION("the same faces on one thread") {
    tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    CHECK(faces_hidden_by_outfit(capsule, sleeve, options).faces == hidden.faces);
  }
  SECTION("with no garment nothing is hidden") {
    const HiddenFaces bare = faces_hidden_by_outfit(capsule, TriangleMesh{}, options);
    CHECK(bare.faces.empty());
    CHECK(bare.kept_escaping == bare.face_count);
  }
  SECTION("a closed garment has no opening") {
    const TriangleMesh shell = closed_cylinder(1.5, -3.0, 3.0, 7, 40);
    const HiddenFaces all = faces_hidden_by_outfit(capsule, shell, options);
    CHECK(all.hidden == all.face_count);
  }
  SECTION("bad options") {
    HiddenFaceOptions bad = options;
    bad.margin = -1.0;
    CHECK_THROWS_AS(faces_hidden_by_outfit(capsule, sleeve, bad), std::invalid_argument);
    bad = options;
    bad.cone_half_angle_degrees = 90.0;
    CHECK_THROWS_AS(faces_hidden_by_outfit(capsule, sleeve, bad), std::invalid_argument);
    bad = options;
    bad.ring_rays = -1;
    CHECK_THROWS_AS(faces_hidden_by_outfit(capsule, sleeve, bad), std::invalid_argument);
  }
}
