#include <filesystem>
#include <fstream>
#include <string>

#include <fmt/format.h>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "report_page/page_colours.hpp"
#include "report_page/page_test_support.hpp"
#include "report_page/rgb_image.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;

namespace {

const std::string kScene = "scenes/dress_form/";

nlohmann::json read_json(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

/// Pixels with a heat-map colour's hue (the garment, under any light).
std::size_t heat_pixels(const gr::RgbImage& image) {
  std::size_t n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (const double t : {0.0, 0.125, 0.25})
        if (gr::test::same_hue(image.at(x, y), gr::heat_colour(t), 10.0)) {
          ++n;
          break;
        }
  return n;
}

}  // namespace

TEST_CASE("retarget writes report.html and, with --png, front and side stills - validate --html",
          "[tools][cli][report_page]") {
  const fs::path out = gr::test::fresh_temp_dir("cli_report_page");
  const gr::test::CliRun run =
      gr::test::run_cli({"retarget", "--garment", gr::test::project_file(kScene + "garment.obj"),
                         "--avatar", gr::test::project_file(kScene + "avatar.obj"), "--no-fit",
                         gr::test::project_file(kScene + "no-fit.txt"), "--quality", "fast",
                         "--quiet", "--png", "--out", (out / "run").string()},
                        "report_page");
  CAPTURE(run.out, run.err);
  REQUIRE(run.exit_code == 0);
  const fs::path dir = out / "run";

  SECTION("the page holds the run's numbers, the input and output garments and the no-fit faces") {
    const std::string html = gr::test::read_text(dir / "report.html");
    const nlohmann::json report = read_json(dir / "report.json");
    CHECK(html.find(fmt::format("<td>{:.3g} avatar units</td>",
                                report["fit_error"]["mean"].get<double>())) != std::string::npos);
    CHECK(html.find(fmt::format("<th>total</th><td>{:.2f} s</td>",
                                report["seconds"]["total"].get<double>())) != std::string::npos);
    CHECK(html.find("class=\"verdict pass\"") != std::string::npos);
    const nlohmann::json scene = gr::test::scene_of(html);
    const auto& garment = scene["garments"][0];
    REQUIRE(garment["shapes"].size() == 2);
    // The bundled garment starts through the dress form's hips and ends clear of it.
    CHECK_FALSE(garment["shapes"][0]["marked"].empty());
    CHECK(garment["shapes"][1]["marked"].empty());
    CHECK(garment["no_fit"].size() == 1008 - report["modelled"]["fit_faces"].get<std::size_t>());
  }

  SECTION("the stills show the garment in heat colours") {
    for (const char* name : {"front.png", "side.png"}) {
      CAPTURE(name);
      const gr::RgbImage image = gr::read_png((dir / name).string());
      CHECK(image.width == 720);
      CHECK(heat_pixels(image) > 5000);
    }
  }

  SECTION("validate --html marks where the input garment crosses the avatar") {
    const fs::path page = out / "validate.html";
    const gr::test::CliRun check = gr::test::run_cli(
        {"validate", "--garment", gr::test::project_file(kScene + "garment.obj"), "--avatar",
         gr::test::project_file(kScene + "avatar.obj"), "--html", page.string()},
        "report_page_validate");
    CHECK(check.exit_code == 1);
    const std::string html = gr::test::read_text(page);
    CHECK(html.find("class=\"verdict fail\"") != std::string::npos);
    const nlohmann::json scene = gr::test::scene_of(html);
    REQUIRE(scene["garments"][0]["shapes"].size() == 1);
    CHECK_FALSE(scene["garments"][0]["shapes"][0]["marked"].empty());
  }
}
