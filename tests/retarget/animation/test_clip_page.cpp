#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "report_page/report_page.hpp"
#include "retarget/animation/animation_check.hpp"
#include "retarget/result_page.hpp"
#include "scenes/synthetic/bending_arm.hpp"
#include "test_support.hpp"
#include "validate/checks/mesh_intersections.hpp"
#include "validate/measure/surface_distance.hpp"

namespace gr {
namespace {

TEST_CASE("the page's clip agrees frame by frame with the clip's exact check",
          "[animation][report_page]") {
  const auto dir = test::fresh_temp_dir("clip_page_bending_arm");
  write_bending_arm_scene(make_bending_arm_scene(90.0), dir.string());
  const std::string sleeve = (dir / "sleeve.glb").string();
  const std::string arm = (dir / "arm.glb").string();
  const AnimatedScene scene = read_animated_scene({sleeve}, {""}, arm, {});
  const ChosenClip clip = choose_clips({"bend"}, arm, 30.0).front();
  ClipPoses poses;
  const ClipFindings findings = check_clip(scene, clip, 30.0, &poses);
  REQUIRE(findings.worst_frame());
  REQUIRE(findings.first_crossing());
  CHECK(*findings.first_crossing() > 0);
  // Keeping the poses changes no finding.
  const ClipFindings plain = check_clip(scene, clip, 30.0);
  REQUIRE(plain.frames.size() == findings.frames.size());
  for (std::size_t f = 0; f < plain.frames.size(); ++f) {
    CHECK(plain.frames[f].total() == findings.frames[f].total());
    CHECK(plain.frames[f].crossing_faces == findings.frames[f].crossing_faces);
  }

  const PageAnimation page = page_animation(findings, poses, scene.avatar.mesh.faces, 1);
  REQUIRE(page.frames.size() == findings.frames.size());
  CHECK(page.first_crossing == findings.first_crossing());
  CHECK(page.worst_frame == findings.worst_frame());
  for (std::size_t f = 0; f < page.frames.size(); ++f) {
    CAPTURE(f);
    const PageFrame& frame = page.frames[f];
    const FrameFindings& found = findings.frames[f];
    CHECK(frame.time == found.time);
    CHECK(frame.avatar_pairs == found.avatar_pairs);
    CHECK(frame.self_pairs == found.self_pairs);
    CHECK(frame.layer_pairs == found.layer_pairs);
    REQUIRE(frame.marked_faces.size() == 1);
    CHECK(frame.marked_faces[0] == found.crossing_faces[0]);
    CHECK(frame.marked_faces[0].empty() == (found.total() == 0));
    CHECK(frame.avatar == poses.avatar[f]);
    CHECK(frame.garments[0] == poses.garments[f][0]);
    // The marks are the faces the exact check finds crossing the posed avatar (the sleeve
    // does not cross itself here).
    const TriangleMesh garment{frame.garments[0], scene.garments[0].mesh.faces};
    const TriangleMesh avatar{frame.avatar, scene.avatar.mesh.faces};
    std::vector<int> crossing;
    for (const FacePair& p : find_intersecting_face_pairs(garment, avatar).pairs)
      crossing.push_back(p.first);
    std::sort(crossing.begin(), crossing.end());
    crossing.erase(std::unique(crossing.begin(), crossing.end()), crossing.end());
    if (found.self_pairs == 0) CHECK(frame.marked_faces[0] == crossing);
    CHECK(frame.distance[0] == distances_to_surface(avatar, frame.garments[0]));
  }
  // The sleeve moves through the clip.
  CHECK((page.frames.back().garments[0] - page.frames.front().garments[0]).norm() > 0.5);

  SECTION("the page's script reads the same frames") {
    ReportPageData data;
    data.title = "sleeve on arm";
    data.avatar = scene.avatar.mesh;
    PageGarment garment;
    garment.name = "sleeve";
    garment.faces = scene.garments[0].mesh.faces;
    garment.shapes.push_back(
        {"as given",
         scene.garments[0].mesh.vertices,
         distances_to_surface(scene.avatar.mesh, scene.garments[0].mesh.vertices),
         {}});
    data.garments.push_back(garment);
    data.animation = page;
    const nlohmann::ordered_json json = report_page_scene(data)["animation"];
    CHECK(json["frame_count"] == findings.frames.size());
    CHECK(json["worst_frame"] == *findings.worst_frame());
    CHECK(json["first_crossing"] == *findings.first_crossing());
    for (std::size_t f = 0; f < findings.frames.size(); ++f) {
      CHECK(json["avatar_pairs"][f] == findings.frames[f].avatar_pairs);
      CHECK(json["self_pairs"][f] == findings.frames[f].self_pairs);
      CHECK(json["garments"][0]["marked"][f].get<std::vector<int>>() ==
            findings.frames[f].crossing_faces[0]);
    }
  }
}

TEST_CASE("a page plays the clip with the most crossing frames, then the most pairs",
          "[animation][report_page]") {
  const auto clip_of = [](std::vector<std::size_t> pairs) {
    ClipFindings clip;
    for (const std::size_t p : pairs) {
      FrameFindings frame;
      frame.avatar_pairs = p;
      clip.frames.push_back(frame);
    }
    return clip;
  };
  const ClipFindings free = clip_of({0, 0, 0});
  const ClipFindings two = clip_of({0, 1, 1});
  const ClipFindings two_worse = clip_of({0, 5, 1});
  const ClipFindings three = clip_of({1, 1, 1});
  CHECK(page_clip({&free}) == 0);
  CHECK(page_clip({&free, &two}) == 1);
  CHECK(page_clip({&two, &two_worse}) == 1);
  CHECK(page_clip({&two_worse, &two}) == 0);
  CHECK(page_clip({&two_worse, &three, &two}) == 1);
  CHECK(page_clip({&free, &free}) == 0);
}

}  // namespace
}  // namespace gr
