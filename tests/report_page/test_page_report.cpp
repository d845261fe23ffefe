// The page's typed schema: what it reads of a real run's report.json and certificate.json,
// and that a renamed or mistyped key is refused instead of shown empty.
#include <filesystem>
#include <string>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "page_test_support.hpp"
#include "report_page/page_report.hpp"
#include "report_page/report_page.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;

namespace {

struct RunDocuments {
  nlohmann::json report;
  nlohmann::ordered_json certificate;
  nlohmann::ordered_json validation;  ///< validate --threshold of the bundled input garment
};

/// The bundled scene retargeted and its input validated once per test process.
const RunDocuments& bundled_run() {
  static const RunDocuments documents = [] {
    const fs::path out = gr::test::fresh_temp_dir("page_report");
    const std::string scene = gr::test::project_file("scenes/dress_form/");
    const gr::test::CliRun run =
        gr::test::run_cli({"retarget", "--garment", scene + "garment.obj", "--avatar",
                           scene + "avatar.obj", "--no-fit", scene + "no-fit.txt", "--quality",
                           "fast", "--quiet", "--out", (out / "run").string()},
                          "page_report");
    CAPTURE(run.out, run.err);
    REQUIRE(run.exit_code == 0);
    const gr::test::CliRun check = gr::test::run_cli(
        {"validate", "--garment", scene + "garment.obj", "--avatar", scene + "avatar.obj",
         "--threshold", "0.01", "--report", (out / "validation.json").string()},
        "page_report_validate");
    REQUIRE(check.exit_code == 1);  // the input crosses the dress form's hips
    return RunDocuments{
        nlohmann::json::parse(gr::test::read_text(out / "run" / "report.json")),
        nlohmann::ordered_json::parse(gr::test::read_text(out / "run" / "certificate.json")),
        nlohmann::ordered_json::parse(gr::test::read_text(out / "validation.json"))};
  }();
  return documents;
}

}  // namespace

TEST_CASE("the page schema reads every part of a real run's report and certificate",
          "[report_page][cli]") {
  const RunDocuments& run = bundled_run();
  const nlohmann::json& json = run.report;
  const gr::PageReport page = gr::read_page_report(run.report, run.certificate);
  REQUIRE(page.run);
  REQUIRE(page.certificate);
  const gr::RunPageReport& r = *page.run;

  SECTION("the run's parts, each as written") {
    CHECK(r.quality == "fast");
    CHECK(r.certified == json["certified"].get<bool>());
    REQUIRE(r.fit_error);
    CHECK(r.fit_error->mean == json["fit_error"]["mean"].get<double>());
    CHECK(r.fit_error->p95 == json["fit_error"]["p95"].get<double>());
    REQUIRE(r.fit);
    CHECK(r.fit->status == json["fit"]["status"]);
    CHECK(r.fit->newton_iterations == json["fit"]["newton_iterations"]);
    REQUIRE(r.inflate);
    CHECK(r.inflate->status == json["inflate"]["status"]);
    CHECK(r.inflate->al_rounds == json["inflate"]["al_rounds"]);
    REQUIRE(r.modelled);
    CHECK(r.modelled->terms == json["modelled"]["terms"].get<std::vector<std::string>>());
    CHECK_FALSE(r.modelled->terms.empty());
    CHECK(r.modelled->fit_faces == json["modelled"]["fit_faces"]);
    CHECK(r.modelled->garment_faces == 1008);
    CHECK(r.modelled->avatar_faces_total == 3440);
    CHECK(r.modelled->self_contact_where == json["modelled"]["self_contact_where"]);
    REQUIRE(r.ease);
    CHECK(r.ease->fit == "tight");
    CHECK(r.ease->source == "none");
    REQUIRE(r.inherited_crossings);
    CHECK(r.inherited_crossings->pairs == json["inherited_crossings"]["pairs"]);
    REQUIRE(r.split_non_manifold_edges);
    CHECK(r.split_non_manifold_edges->edges == json["split_non_manifold_edges"]["edges"]);
    REQUIRE(r.pierced_faces);
    CHECK(r.pierced_faces->bones.size() == json["pierced_faces"]["bones"].size());
    CHECK(r.min_distance == json["min_distance"]["avatar_units"].get<double>());
    REQUIRE(r.shape);
    CHECK(r.shape->mean_edge_change == json["shape"]["mean_edge_change"].get<double>());
    CHECK(r.shape->area_change == json["shape"]["area_change"].get<double>());
    CHECK(r.shape->surface_energy_per_area ==
          json["shape"]["surface_energy_per_area"].get<double>());
    CHECK(r.loop_offsets.size() == json["position"]["loop_offsets"].size());
    REQUIRE(r.shrink);
    CHECK(r.shrink->mode == json["shrink"]["mode"]);
    REQUIRE(r.seconds.size() == 8);
    CHECK(r.seconds.back().stage == "total");
    CHECK(r.seconds.back().seconds == json["seconds"]["total"].get<double>());
    CHECK(r.peak_memory_mb == json["peak_memory_mb"].get<double>());
    CHECK(r.warnings == json["warnings"].get<std::vector<std::string>>());
  }

  SECTION("the certificate's verdict, counts, garments and messages") {
    const gr::CertificatePageReport& c = *page.certificate;
    CHECK(c.kind == "certificate");
    CHECK(c.certified == true);
    REQUIRE(c.counts);
    CHECK(c.counts->garment_avatar_intersections == 0);
    REQUIRE(c.garments.size() == 1);
    CHECK(c.garments[0].path == run.certificate["garments"][0]["path"]);
    CHECK(c.garments[0].avatar_clearance ==
          run.certificate["garments"][0]["avatar_clearance"]["distance"].get<double>());
    CHECK_FALSE(c.garments[0].near_vertices);
    CHECK(c.messages.size() == run.certificate["issues"]["messages"].size());
    CHECK_FALSE(c.messages.empty());
  }

  SECTION("a validation report of a crossing garment, with near vertices") {
    const gr::PageReport checked = gr::read_page_report(nullptr, run.validation);
    CHECK_FALSE(checked.run);
    REQUIRE(checked.certificate);
    const gr::CertificatePageReport& c = *checked.certificate;
    CHECK(c.kind == "validation_report");
    CHECK(c.certified == false);
    REQUIRE(c.garments.size() == 1);
    CHECK(c.garments[0].avatar_intersections > 0);
    CHECK(c.garments[0].avatar_intersections ==
          c.counts.value_or(gr::CertificateCounts{}).garment_avatar_intersections);
    REQUIRE(c.garments[0].near_vertices);
    CHECK(c.garments[0].near_vertices->threshold == 0.01);
    CHECK(c.garments[0].near_vertices->count > 0);
  }
}

TEST_CASE("a renamed or mistyped key of a real run's documents is refused by its address",
          "[report_page][cli]") {
  const RunDocuments& run = bundled_run();
  nlohmann::json report = run.report;
  nlohmann::ordered_json certificate = run.certificate;
  std::string address;

  SECTION("a renamed report key") {
    report["ease"]["fitted"] = report["ease"]["fit"];
    report["ease"].erase("fit");
    address = "report.json /ease/fit is missing";
  }
  SECTION("a count written as text") {
    report["fit"]["newton_iterations"] = "22";
    address = "report.json /fit/newton_iterations is not a whole number";
  }
  SECTION("a count written as a fraction") {
    report["inherited_crossings"]["pairs"] = 1.5;
    address = "report.json /inherited_crossings/pairs is not a whole number";
  }
  SECTION("a length written as text") {
    report["fit_error"]["mean"] = "0.01";
    address = "report.json /fit_error/mean is not a number";
  }
  SECTION("a list of bones holding a number") {
    report["pierced_faces"]["bones"] = {1};
    address = "report.json /pierced_faces/bones holds a value that is not a string";
  }
  SECTION("a stage time missing") {
    report["seconds"].erase("shrink");
    address = "report.json /seconds/shrink is missing";
  }
  SECTION("warnings as one text") {
    report["warnings"] = "careful";
    address = "report.json /warnings is not a list";
  }
  SECTION("a renamed certificate key") {
    certificate["garments"][0]["clearance"] = certificate["garments"][0]["avatar_clearance"];
    certificate["garments"][0].erase("avatar_clearance");
    address = "certificate /garments/0/avatar_clearance is missing";
  }
  SECTION("a certificate verdict as text") {
    certificate["certified"] = "true";
    address = "certificate /certified is not true or false";
  }
  SECTION("a message without its severity") {
    certificate["issues"]["messages"][0].erase("severity");
    address = "certificate /issues/messages/0/severity is missing";
  }
  CAPTURE(address);
  CHECK_THROWS_WITH(gr::read_page_report(report, certificate), Catch::Contains(address));
  // The page is refused too, rather than shown with that row empty.
  gr::ReportPageData data = gr::test::small_page_scene();
  data.report = report;
  data.certificate = certificate;
  CHECK_THROWS_AS(gr::report_page_html(data), std::invalid_argument);
}

TEST_CASE("parts a document leaves out stay empty, and a null number reads as none",
          "[report_page]") {
  nlohmann::json report = gr::test::sample_report();
  for (const char* part : {"ease", "shape", "seconds", "pierced_faces", "warnings"})
    report.erase(part);
  report["fit_error"]["p95"] = nullptr;  // a NaN as the documents write it
  const gr::PageReport page = gr::read_page_report(report, nullptr);
  REQUIRE(page.run);
  CHECK_FALSE(page.certificate);
  CHECK_FALSE(page.run->ease);
  CHECK_FALSE(page.run->shape);
  CHECK_FALSE(page.run->pierced_faces);
  CHECK(page.run->seconds.empty());
  CHECK(page.run->warnings.empty());
  REQUIRE(page.run->fit_error);
  CHECK(page.run->fit_error->mean == 0.00123);
  CHECK_FALSE(page.run->fit_error->p95);
  CHECK(page.run->inherited_crossings->attached_pieces == 1);

  gr::ReportPageData data = gr::test::small_page_scene();
  data.report = report;
  const std::string html = gr::report_page_html(data);
  CHECK(html.find("<tr><th>95th percentile</th><td>—</td></tr>") != std::string::npos);
  CHECK(html.find("<h2>Stage times</h2>\n</section>") != std::string::npos);
  CHECK_THROWS_AS(gr::read_page_report(nlohmann::json::array(), nullptr), std::invalid_argument);
}

TEST_CASE("every part of the sample documents shows on the page", "[report_page]") {
  gr::ReportPageData data = gr::test::small_page_scene();
  data.report = gr::test::sample_report();
  data.certificate = gr::test::sample_certificate();
  const std::string html = gr::report_page_html(data);
  for (const char* row :
       {"<th>fit faces</th><td>864 of 960</td>",
        "<th>fit solve</th><td>converged (12 Newton steps)</td>",
        "<th>fit</th><td>ease (source ease: source body)</td>",
        "<th>ease kept, median ratio</th><td>0.9</td>",
        "<th>vertices within 25% of their source ease</th><td>75.00%</td>",
        "<th>self-crossing face pairs kept (inherited)</th><td>4, 2 still crossing</td>",
        "<th>pieces through another piece, attached to it</th><td>1</td>",
        "<td>3, 1 opened (not written); bones through them: Hips-Spine</td>",
        "<th>edges of more than two faces, split and welded back</th><td>3 (6 vertex copies)</td>",
        "<th>area change</th><td>5.00%</td>",
        "<th>boundary loops off their place</th><td>2 loops, worst 3.00% of its bone</td>",
        "<th>shrink</th><td>levelset (depth 0.04)</td>",
        "<th>inflation</th><td>snapped (2 rounds, 0 resets, 7 Newton steps)</td>",
        "<th>terms</th><td>stretch, contact</td>",
        "<th>avatar faces modelled</th><td>640 of 1280</td>",
        "<th>self-contact</th><td>everywhere</td>", "<th>peak memory</th><td>80 MB</td>",
        "<th>certify</th><td>0.40 s</td>",
        "0 garment–avatar, 0 self and 0 garment–garment intersecting face pairs"}) {
    CAPTURE(row);
    CHECK(html.find(row) != std::string::npos);
  }
}
