#include <filesystem>

#include <catch2/catch.hpp>

#include "core/common/errors.hpp"
#include "page_test_support.hpp"
#include "report_page/page_colours.hpp"
#include "report_page/still_image.hpp"
#include "test_support.hpp"

namespace {

/// Pixels that differ from the background.
std::size_t drawn_pixels(const gr::RgbImage& image) {
  std::size_t n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) n += image.at(x, y) == gr::kBackgroundColour ? 0 : 1;
  return n;
}

std::size_t pixels_like(const gr::RgbImage& image, gr::Rgb8 colour) {
  std::size_t n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      n += gr::test::same_hue(image.at(x, y), colour, 8.0) ? 1 : 0;
  return n;
}

}  // namespace

TEST_CASE("still images show the garment in its heat colours on the avatar", "[report_page][png]") {
  const gr::ReportPageData data = gr::test::small_page_scene();
  gr::StillOptions options;
  options.width = 240;
  options.height = 320;
  const gr::StillView view = GENERATE(gr::StillView::kFront, gr::StillView::kSide);
  const gr::RgbImage image = gr::render_still(data, view, options);
  REQUIRE(image.width == 240);
  REQUIRE(image.height == 320);

  SECTION("the figure fills the image but not all of it") {
    const double covered = static_cast<double>(drawn_pixels(image)) / (240.0 * 320.0);
    CHECK(covered > 0.1);
    CHECK(covered < 0.9);
  }

  SECTION("a garment vertex facing the viewer shows its heat colour") {
    const gr::StillCamera camera = gr::still_camera(data, view, options.width, options.height);
    const gr::GarmentShape& shape = data.garments[0].shapes.back();
    // The output vertex nearest the viewer on the middle ring (rings 0 and 4 are the hems).
    Eigen::Index best = -1;
    for (Eigen::Index v = 2 * 48; v < 3 * 48; ++v)
      if (best < 0 || camera.project(shape.vertices.row(v).transpose()).z() >
                          camera.project(shape.vertices.row(best).transpose()).z())
        best = v;
    const gr::Vector3d p = camera.project(shape.vertices.row(best).transpose());
    const gr::Rgb8 seen = image.at(static_cast<int>(p.x()), static_cast<int>(p.y()));
    const gr::Rgb8 expected =
        gr::heat_colour(shape.distance[static_cast<std::size_t>(best)] / 0.02);
    CAPTURE(p.x(), p.y(), int(seen.r), int(seen.g), int(seen.b), int(expected.r), int(expected.g),
            int(expected.b));
    CHECK(gr::test::same_hue(seen, expected));
  }

  SECTION("no-fit faces in their colour, the avatar grey, nothing marked on the output") {
    CHECK(pixels_like(image, gr::kNoFitColour) > 50);
    CHECK(pixels_like(image, gr::kMarkedColour) == 0);
    const gr::Rgb8 top = image.at(options.width / 2, static_cast<int>(0.15 * options.height));
    CHECK(gr::test::hue_saturation(top).second < 0.05);
    CHECK(top != gr::kBackgroundColour);
  }

  SECTION("marked faces are drawn in the marked colour") {
    gr::ReportPageData marked = data;
    marked.garments[0].shapes.back().marked_faces = {180, 181, 182,
                                                     183, 184, 185};  // facing -y and +x
    CHECK(pixels_like(gr::render_still(marked, view, options), gr::kMarkedColour) > 0);
  }

  SECTION("without a garment no heat colour appears") {
    gr::ReportPageData bare = data;
    bare.garments.clear();
    const gr::RgbImage avatar_only = gr::render_still(bare, view, options);
    CHECK(pixels_like(avatar_only, gr::heat_colour(0.25)) == 0);
    CHECK(pixels_like(image, gr::heat_colour(0.25)) > 100);
  }
}

TEST_CASE("PNG files round-trip through libpng", "[report_page][png]") {
  const gr::ReportPageData data = gr::test::small_page_scene();
  gr::StillOptions options;
  options.width = 120;
  options.height = 160;
  const auto dir = gr::test::fresh_temp_dir("still_png");
  const std::string front = (dir / "front.png").string();
  const std::string side = (dir / "side.png").string();
  gr::write_still_images(data, front, side, options);
  const gr::RgbImage read = gr::read_png(front);
  const gr::RgbImage rendered = gr::render_still(data, gr::StillView::kFront, options);
  CHECK(read.width == 120);
  CHECK(read.height == 160);
  CHECK(read.pixels == rendered.pixels);
  CHECK(gr::read_png(side).pixels == gr::render_still(data, gr::StillView::kSide, options).pixels);
  CHECK_THROWS_AS(gr::read_png((dir / "missing.png").string()), gr::InputError);
  CHECK_THROWS_AS(gr::encode_png(gr::RgbImage()), gr::OutputError);
}
