#include <algorithm>
#include <cmath>
#include <string>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "core/mesh/primitives.hpp"
#include "page_test_support.hpp"
#include "report_page/page_animation.hpp"
#include "report_page/report_page.hpp"

namespace {

/// A made-up clip on the small scene: the garment rises by `rise` per frame and the avatar
/// turns about its up axis; frames from `crossing_from` on cross, the most in `worst`.
gr::PageAnimation small_clip(const gr::ReportPageData& data, std::size_t frames,
                             std::size_t crossing_from, std::size_t worst, double rise = 0.01) {
  gr::PageAnimation clip;
  clip.clip = "rise & <turn>";
  clip.fps = 30.0;
  const gr::PageGarment& garment = data.garments.front();
  for (std::size_t f = 0; f < frames; ++f) {
    gr::PageFrame frame;
    frame.time = static_cast<double>(f) / clip.fps;
    const double angle = 0.05 * static_cast<double>(f);
    frame.avatar = data.avatar.vertices;
    for (Eigen::Index v = 0; v < frame.avatar.rows(); ++v) {
      const double x = data.avatar.vertices(v, 0), z = data.avatar.vertices(v, 2);
      frame.avatar(v, 0) = std::cos(angle) * x - std::sin(angle) * z;
      frame.avatar(v, 2) = std::sin(angle) * x + std::cos(angle) * z;
    }
    gr::MatrixX3d posed = garment.shapes.back().vertices;
    posed.col(1).array() += rise * static_cast<double>(f);
    frame.garments = {posed};
    frame.distance = {std::vector<double>(static_cast<std::size_t>(posed.rows()),
                                          0.001 * static_cast<double>(f))};
    frame.marked_faces = {{}};
    if (f >= crossing_from) {
      frame.avatar_pairs = f == worst ? 9 : 2;
      frame.self_pairs = 1;
      frame.marked_faces = {{static_cast<int>(f % garment.faces.rows()), 0}};
    }
    clip.frames.push_back(std::move(frame));
  }
  if (crossing_from < frames) {
    clip.first_crossing = crossing_from;
    clip.worst_frame = worst;
  }
  return clip;
}

/// The #P×3 positions an encode_positions entry holds, decoded as the page's script does.
gr::MatrixX3d decoded_positions(const nlohmann::json& entry) {
  const std::vector<std::uint32_t> q =
      gr::test::unpack(gr::test::decode_base64(entry["data"].get<std::string>()), 2);
  gr::MatrixX3d out(static_cast<Eigen::Index>(q.size() / 3), 3);
  for (std::size_t i = 0; i < q.size(); ++i) {
    const int axis = static_cast<int>(i % 3);
    const double lo = entry["min"][axis], hi = entry["max"][axis];
    out(static_cast<Eigen::Index>(i / 3), axis) = lo + q[i] / 65535.0 * (hi - lo);
  }
  return out;
}

/// The largest error encode_positions allows for an entry: half a step of its widest side.
double quantization_bound(const nlohmann::json& entry) {
  double side = 0.0;
  for (int axis = 0; axis < 3; ++axis)
    side = std::max(side, entry["max"][axis].get<double>() - entry["min"][axis].get<double>());
  return side / 131070.0 * (1.0 + 1e-9);
}

}  // namespace

TEST_CASE("a page's clip carries every frame's counts, marks and posed meshes",
          "[report_page][animation]") {
  gr::ReportPageData data = gr::test::small_page_scene();
  const gr::ReportPageData still = data;
  data.animation = small_clip(data, 12, 4, 7);
  const nlohmann::json scene = gr::test::scene_of(gr::report_page_html(data));
  REQUIRE(scene.contains("animation"));
  const nlohmann::json& clip = scene["animation"];
  CHECK(clip["clip"] == "rise & <turn>");
  CHECK(clip["fps"] == 30.0);
  CHECK(clip["frame_count"] == 12);
  CHECK(clip["first_crossing"] == 4);
  CHECK(clip["worst_frame"] == 7);
  for (std::size_t f = 0; f < 12; ++f) {
    CAPTURE(f);
    const gr::PageFrame& frame = data.animation->frames[f];
    CHECK(clip["times"][f].get<double>() == frame.time);
    CHECK(clip["avatar_pairs"][f] == frame.avatar_pairs);
    CHECK(clip["self_pairs"][f] == frame.self_pairs);
    CHECK(clip["layer_pairs"][f] == frame.layer_pairs);
    CHECK(clip["garments"][0]["marked"][f].get<std::vector<int>>() == frame.marked_faces[0]);
  }

  SECTION("positions decode to the posed meshes within 16-bit quantization") {
    const gr::MatrixX3d garment = decoded_positions(clip["garments"][0]["positions"]);
    const Eigen::Index n = data.garments.front().shapes.back().vertices.rows();
    REQUIRE(garment.rows() == 12 * n);
    const gr::MatrixX3d avatar = decoded_positions(clip["avatar"]["positions"]);
    const std::vector<std::size_t> keys = clip["avatar"]["frames"];
    CHECK(keys.size() == 12);  // a small avatar is kept in every frame
    const Eigen::Index na = data.avatar.vertices.rows();
    REQUIRE(avatar.rows() == static_cast<Eigen::Index>(keys.size()) * na);
    for (const std::size_t f : {0, 5, 11}) {
      CAPTURE(f);
      const gr::PageFrame& frame = data.animation->frames[f];
      const Eigen::Index fi = static_cast<Eigen::Index>(f);
      CHECK((garment.middleRows(fi * n, n) - frame.garments[0]).cwiseAbs().maxCoeff() <=
            quantization_bound(clip["garments"][0]["positions"]));
      CHECK((avatar.middleRows(fi * na, na) - frame.avatar).cwiseAbs().maxCoeff() <=
            quantization_bound(clip["avatar"]["positions"]));
    }
    // The garment moves between frames by more than the quantization.
    CHECK((garment.middleRows(11 * n, n) - garment.topRows(n)).cwiseAbs().maxCoeff() > 0.1);
  }

  SECTION("the slider's ticks mark the crossing frames, the first and the worst apart") {
    const std::string html = gr::report_page_html(data);
    CHECK(html.find("id=\"gr-player\"") != std::string::npos);
    CHECK(html.find("max=\"11\"") != std::string::npos);
    std::size_t ticks = 0;
    for (auto at = html.find("<i class=\"mark"); at != std::string::npos;
         at = html.find("<i class=\"mark", at + 1))
      ++ticks;
    CHECK(ticks == 8);
    CHECK(gr::test::between(html, "id=\"gr-mark-worst\" data-frame=\"", "\"") == "7");
    CHECK(gr::test::between(html, "id=\"gr-mark-first\" data-frame=\"", "\"") == "4");
    CHECK(gr::test::between(html, "id=\"gr-worst\" data-frame=\"", "\"") == "7");
    CHECK(html.find("rise &amp; &lt;turn&gt;") != std::string::npos);
  }

  SECTION("a page without a clip has the scene and the markup it had") {
    const std::string html = gr::report_page_html(still);
    CHECK(html.find("gr-player") == std::string::npos);
    nlohmann::json without = scene;
    without.erase("animation");
    CHECK(gr::test::scene_of(html) == without);
    CHECK_FALSE(gr::report_page_scene(still).contains("animation"));
  }

  SECTION("frames that do not match the page are refused") {
    data.animation->frames[3].garments[0].conservativeResize(5, 3);
    CHECK_THROWS_AS(gr::report_page_html(data), std::invalid_argument);
    data = still;
    data.animation = small_clip(data, 3, 0, 1);
    data.animation->frames[1].marked_faces[0] = {static_cast<int>(data.garments[0].faces.rows())};
    CHECK_THROWS_AS(gr::report_page_html(data), std::invalid_argument);
  }
}

TEST_CASE("a page's clip keeps its positions within the size budget", "[report_page][animation]") {
  // The dress through the idle clip on body.001: every frame of both fits.
  CHECK(gr::avatar_frame_stride(252, 4230, 1246) == 1);
  // A larger avatar is kept every few frames, the garments in every one.
  const std::size_t stride = gr::avatar_frame_stride(252, 40000, 4000);
  CHECK(stride > 1);
  const auto bytes = [](std::size_t stride) {
    return (gr::avatar_key_frames(252, stride).size() * 40000 + 252 * 4000) * 6;
  };
  CHECK(bytes(stride) <= gr::kAnimationPositionBytes);
  CHECK(bytes(stride - 1) > gr::kAnimationPositionBytes);
  const std::vector<std::size_t> keys = gr::avatar_key_frames(10, 4);
  CHECK(keys == std::vector<std::size_t>{0, 4, 8, 9});
  CHECK(gr::avatar_key_frames(9, 4) == std::vector<std::size_t>{0, 4, 8});

  SECTION("as encoded on a page") {
    gr::ReportPageData data = gr::test::small_page_scene();
    data.avatar = gr::icosphere(6);  // 40962 vertices
    const std::size_t frames = 60;
    data.animation = small_clip(data, frames, 10, 20);
    const std::size_t avatar_vertices = static_cast<std::size_t>(data.avatar.vertices.rows());
    const std::size_t garment_vertices =
        static_cast<std::size_t>(data.garments[0].shapes[0].vertices.rows());
    const std::size_t page_stride =
        gr::avatar_frame_stride(frames, avatar_vertices, garment_vertices);
    CAPTURE(page_stride);
    CHECK(page_stride > 1);
    const nlohmann::ordered_json clip = gr::report_page_scene(data)["animation"];
    const std::size_t base64 = clip["avatar"]["positions"]["data"].get<std::string>().size() +
                               clip["garments"][0]["positions"]["data"].get<std::string>().size();
    // 4/3 of the budget in base64.
    CHECK(base64 <= gr::kAnimationPositionBytes * 4 / 3 + 8);
    CHECK(clip["avatar"]["frames"].size() == gr::avatar_key_frames(frames, page_stride).size());
    CHECK(clip["avatar"]["frames"].back() == frames - 1);
  }
}
