#include <algorithm>
#include <filesystem>
#include <regex>
#include <string>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "page_test_support.hpp"
#include "report_page/benchmark_page.hpp"
#include "report_page/page_assets.hpp"
#include "report_page/page_colours.hpp"
#include "report_page/report_page.hpp"
#include "report_page/view_frame.hpp"

namespace {

std::size_t count_of(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

/// Every http:// or https:// address in a text.
std::vector<std::string> web_addresses(const std::string& text) {
  const std::regex address(R"(https?://[^\s"'<>)]*)", std::regex::icase);
  std::vector<std::string> found;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), address);
       it != std::sregex_iterator(); ++it)
    found.push_back(it->str());
  return found;
}

}  // namespace

TEST_CASE("the report page is one HTML file carrying its script, licence and scene",
          "[report_page]") {
  gr::ReportPageData data = gr::test::small_page_scene();
  data.report = gr::test::sample_report();
  data.certificate = gr::test::sample_certificate();
  const std::string html = gr::report_page_html(data);

  SECTION("a single well-formed document") {
    CHECK(html.rfind("<!DOCTYPE html>\n<html lang=\"en\">", 0) == 0);
    CHECK(html.size() > gr::viewer_script().size());
    CHECK(html.substr(html.size() - 8) == "</html>\n");
    for (const char* tag :
         {"<html", "</html>", "<head>", "</head>", "<body>", "</body>", "<main", "</main>"})
      CHECK(count_of(html, tag) == 1);
    CHECK(count_of(html, "<script") == 2);
    CHECK(count_of(html, "</script>") == 2);
    CHECK(count_of(html, "<section") == count_of(html, "</section>"));
    CHECK(count_of(html, "<details") == count_of(html, "</details>"));
    CHECK(count_of(html, "<table>") == count_of(html, "</table>"));
  }

  SECTION("nothing is loaded from elsewhere") {
    CHECK(html.find("Content-Security-Policy") != std::string::npos);
    CHECK(html.find("default-src 'none'") != std::string::npos);
    CHECK(count_of(html, " src=") == 0);
    CHECK(count_of(html, "<link") == 1);
    CHECK(html.find("<link rel=\"icon\" href=\"data:,\">") != std::string::npos);
    // three.js names the XHTML namespace for document.createElementNS: an identifier,
    // never fetched. No other address may appear.
    for (const std::string& address : web_addresses(html)) {
      CAPTURE(address);
      CHECK(address == "http://www.w3.org/1999/xhtml");
    }
    CHECK(html.find("import(") == std::string::npos);
  }

  SECTION("three.js and its licence are inside") {
    CHECK(html.find(std::string(gr::viewer_script())) != std::string::npos);
    CHECK(html.find("Permission is hereby granted, free of charge") != std::string::npos);
    CHECK(html.find("three.js " + std::string(gr::three_version())) != std::string::npos);
    CHECK(gr::three_version() == "0.187.0");
  }

  SECTION("the scene decodes to the meshes given, within the quantization") {
    const nlohmann::json scene = gr::test::scene_of(html);
    CHECK(scene["heat_range"].get<double>() == Approx(0.02));
    CHECK(scene["view"]["up"] == nlohmann::json::array({0.0, 0.0, 1.0}));
    const auto& garment = scene["garments"][0];
    REQUIRE(garment["shapes"].size() == 2);
    CHECK(garment["shapes"][0]["label"] == "input");
    CHECK(garment["shapes"][1]["marked"].empty());
    CHECK(garment["shapes"][0]["marked"].size() ==
          static_cast<std::size_t>(data.garments[0].faces.rows()));
    CHECK(garment["no_fit"].size() == 96);
    const auto faces = gr::test::unpack(gr::test::decode_base64(garment["faces"]["data"]), 2);
    REQUIRE(faces.size() == static_cast<std::size_t>(data.garments[0].faces.size()));
    for (std::size_t i = 0; i < faces.size(); ++i)
      CHECK(faces[i] == static_cast<std::uint32_t>(data.garments[0].faces(
                            static_cast<Eigen::Index>(i / 3), static_cast<Eigen::Index>(i % 3))));
    const auto& shape = garment["shapes"][1];
    const auto q = gr::test::unpack(gr::test::decode_base64(shape["positions"]["data"]), 2);
    const gr::MatrixX3d& v = data.garments[0].shapes[1].vertices;
    REQUIRE(q.size() == static_cast<std::size_t>(v.size()));
    for (Eigen::Index i = 0; i < v.rows(); ++i)
      for (int a = 0; a < 3; ++a) {
        const double lo = shape["positions"]["min"][a], hi = shape["positions"]["max"][a];
        const double decoded = lo + q[static_cast<std::size_t>(3 * i + a)] / 65535.0 * (hi - lo);
        CHECK(decoded == Approx(v(i, a)).margin((hi - lo) / 65535.0));
      }
    const auto d = gr::test::unpack(gr::test::decode_base64(shape["distance"]["data"]), 2);
    const double max = shape["distance"]["max"];
    for (std::size_t i = 0; i < d.size(); ++i)
      CHECK(d[i] / 65535.0 * max ==
            Approx(data.garments[0].shapes[1].distance[i]).margin(max / 65535.0));
  }

  SECTION("the report's numbers and the verdict are beside the view, escaped") {
    CHECK(html.find("class=\"verdict pass\"") != std::string::npos);
    CHECK(html.find("<td>0.00123 avatar units</td>") != std::string::npos);
    CHECK(html.find("<td>0.00456 avatar units</td>") != std::string::npos);
    CHECK(html.find("<td>0.00071 avatar units</td>") != std::string::npos);
    CHECK(html.find("<td>0.00077 avatar units</td>") != std::string::npos);
    CHECK(html.find("<td>12.34%</td>") != std::string::npos);
    CHECK(html.find("<th>inflate</th><td>1.25 s</td>") != std::string::npos);
    CHECK(html.find("<th>total</th><td>4.75 s</td>") != std::string::npos);
    CHECK(html.find("fit stopped &lt;early&gt; &amp; &quot;soon&quot;") != std::string::npos);
    CHECK(html.find("fit stopped <early>") == std::string::npos);
    CHECK(html.find("id=\"gr-shape-0\">input</button>") != std::string::npos);
    CHECK(html.find("id=\"gr-shape-1\">output</button>") != std::string::npos);
  }

  SECTION("a failed certificate says so") {
    data.certificate["certified"] = false;
    CHECK(gr::report_page_html(data).find("class=\"verdict fail\"") != std::string::npos);
  }

  SECTION("text in the scene cannot close its script element") {
    data.garments[0].name = "</script><script>alert(1)</script>";
    const std::string page = gr::report_page_html(data);
    CHECK(count_of(page, "</script>") == 2);
    CHECK(gr::test::scene_of(page)["garments"][0]["name"] == data.garments[0].name);
  }

  SECTION("inconsistent data is refused") {
    data.garments[0].shapes[1].distance.pop_back();
    CHECK_THROWS_AS(gr::report_page_html(data), std::invalid_argument);
    data = gr::test::small_page_scene();
    data.garments[0].shapes[0].marked_faces.push_back(
        static_cast<int>(data.garments[0].faces.rows()));
    CHECK_THROWS_AS(gr::report_page_html(data), std::invalid_argument);
  }

  SECTION("written atomically as built") {
    const auto dir = gr::test::fresh_temp_dir("report_page");
    gr::write_report_page((dir / "report.html").string(), data);
    CHECK(gr::test::read_text(dir / "report.html") == html);
  }
}

TEST_CASE("the heat map runs from red on the body to blue at the range", "[report_page]") {
  const auto& stops = gr::heat_stops();
  CHECK(gr::heat_colour(0.0) == stops.front().colour);
  CHECK(gr::heat_colour(-1.0) == stops.front().colour);
  CHECK(gr::heat_colour(0.5) == stops[2].colour);
  CHECK(gr::heat_colour(1.0) == stops.back().colour);
  CHECK(gr::heat_colour(7.0) == stops.back().colour);
  CHECK(gr::heat_colour(std::nan("")) == stops.back().colour);
  const gr::Rgb8 between = gr::heat_colour(0.125);
  CHECK(between == gr::Rgb8{205, 55, 53});
  for (const auto& stop : stops) CHECK(gr::test::hue_saturation(stop.colour).second > 0.3);
}

TEST_CASE("the view frame stands a figure up whichever axis is up", "[report_page]") {
  gr::MatrixX3d y_up(2, 3), z_up(2, 3);
  y_up << -0.3, 0, -0.1, 0.3, 1.8, 0.1;
  z_up << -0.3, -0.1, 0, 0.3, 0.1, 1.8;
  const gr::ViewFrame a = gr::guess_view_frame(y_up);
  CHECK(a.up == gr::Vector3d::UnitY());
  CHECK(a.front == gr::Vector3d::UnitZ());
  const gr::ViewFrame b = gr::guess_view_frame(z_up);
  CHECK(b.up == gr::Vector3d::UnitZ());
  CHECK(b.front == -gr::Vector3d::UnitY());
  CHECK(b.side.cross(b.up) == b.front);
}

TEST_CASE("the benchmark page embeds its plot and escapes its table", "[report_page]") {
  gr::BenchmarkPageData data;
  data.title = "speed against accuracy";
  data.columns = {"scene", "config", "total s"};
  data.rows = {{"dress_form", "fast", "0.61"}, {"a<b", "x&y", "1"}};
  data.row_pages = {"runs/dress_form_fast/report.html", ""};
  data.link_column = 1;
  data.plot_png = std::string("\x89PNG\r\n\x1a\n", 8) + "rest";
  data.plot_caption = "time against fit error";
  const std::string html = gr::benchmark_page_html(data);
  CHECK(html.find("src=\"data:image/png;base64,iVBORw0KGgpyZXN0\"") != std::string::npos);
  CHECK(html.find("<td>dress_form</td><td><a href=\"runs/dress_form_fast/report.html\">fast</a>") !=
        std::string::npos);
  CHECK(html.find("<td>a&lt;b</td><td>x&amp;y</td>") != std::string::npos);
  CHECK(web_addresses(html).empty());
  CHECK(count_of(html, "<script") == 0);
  data.link_column = 3;
  CHECK_THROWS_AS(gr::benchmark_page_html(data), std::invalid_argument);
  data.link_column = 1;
  data.rows[1].pop_back();
  CHECK_THROWS_AS(gr::benchmark_page_html(data), std::invalid_argument);
}

TEST_CASE("an outfit page has a box per garment, a one-garment page none",
          "[report_page][outfit]") {
  gr::ReportPageData data = gr::test::small_page_scene();
  data.report = gr::test::sample_report();
  const std::string single = gr::report_page_html(data);
  CHECK(count_of(single, "class=\"garment-toggle\"") == 0);
  CHECK(single.find("id=\"gr-garment-0\"") == std::string::npos);

  gr::PageGarment coat = data.garments[0];
  coat.name = "coat <wool>";
  for (gr::GarmentShape& shape : coat.shapes) shape.vertices *= 1.2;
  data.garments.push_back(coat);
  const std::string outfit = gr::report_page_html(data);
  CHECK(count_of(outfit, "class=\"garment-toggle\"") == 2);
  CHECK(outfit.find("<label><input type=\"checkbox\" class=\"garment-toggle\" "
                    "data-garment=\"0\" id=\"gr-garment-0\" checked> skirt</label>") !=
        std::string::npos);
  CHECK(outfit.find("<label><input type=\"checkbox\" class=\"garment-toggle\" "
                    "data-garment=\"1\" id=\"gr-garment-1\" checked> coat &lt;wool&gt;</label>") !=
        std::string::npos);
  CHECK(outfit.find("id=\"gr-garment-2\"") == std::string::npos);
  CHECK(gr::test::scene_of(outfit)["garments"].size() == 2);
}
