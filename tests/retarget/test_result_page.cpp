// The report the run writes against the schema its page reads (report_page/page_report.hpp):
// every part the page shows, under the keys and types it reads them with.
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "report_page/page_report.hpp"
#include "retarget/report.hpp"

using namespace gr;

TEST_CASE("the page reads what the run's report writes, part by part", "[report_page][report]") {
  RetargetReport report;
  report.quality = Quality::kFast;
  report.seconds.total = 4.5;
  report.peak_memory_mb = 81.0;
  report.normalize.garment_faces = 960;
  report.normalize.avatar_faces_total = 1280;
  report.repairs.non_manifold.edges = 3;
  report.repairs.non_manifold.vertex_copies = 6;
  report.repairs.crossings.pairs = 4;
  report.repairs.crossings.still_crossing = 2;
  report.repairs.crossings.attached_pieces = 1;
  report.shrink.depth = 0.04;
  report.repairs.pierced.document_faces = {5, 6, 7};
  report.repairs.pierced.opened_document_faces = {6};
  report.repairs.pierced.bones = {"Hips-Spine"};
  report.inflate.status = "snapped";
  report.inflate.al_rounds = 2;
  report.fit.status = "converged";
  report.fit.newton_iterations = 12;
  report.fit.terms = {"stretch", "contact"};
  report.fit.fit_faces = 864;
  report.fit.avatar_faces_modelled = 640;
  report.fit.loop_offsets = {0.01, 0.03};
  report.fit.surface_energy_per_area = 0.002;
  report.ease.measure.vertices = 400;
  report.ease.measure.median_ratio = 0.9;
  report.certify.fit_error.mean = 0.00123;
  report.certify.certified = true;
  report.warnings = {"fit stopped early"};

  const PageReport page = read_page_report(to_json(report), nullptr);
  REQUIRE(page.run);
  const RunPageReport& r = *page.run;
  CHECK(r.quality == "fast");
  CHECK(r.certified == true);
  REQUIRE(r.fit_error);
  CHECK(r.fit_error->mean == 0.00123);
  REQUIRE(r.fit);
  CHECK(r.fit->status == "converged");
  CHECK(r.fit->newton_iterations == 12);
  REQUIRE(r.inflate);
  CHECK(r.inflate->status == "snapped");
  CHECK(r.inflate->al_rounds == 2);
  REQUIRE(r.modelled);
  CHECK(r.modelled->terms == std::vector<std::string>{"stretch", "contact"});
  CHECK(r.modelled->garment_faces == 960);
  CHECK(r.modelled->fit_faces == 864);
  CHECK(r.modelled->avatar_faces_total == 1280);
  CHECK(r.modelled->avatar_faces_modelled == 640);
  CHECK(r.modelled->self_contact_where == "where the garment can fold onto itself");
  REQUIRE(r.ease);
  CHECK(r.ease->measured_vertices == 400);
  CHECK(r.ease->median_ratio == 0.9);
  REQUIRE(r.inherited_crossings);
  CHECK(r.inherited_crossings->pairs == 4);
  CHECK(r.inherited_crossings->still_crossing == 2);
  CHECK(r.inherited_crossings->attached_pieces == 1);
  REQUIRE(r.split_non_manifold_edges);
  CHECK(r.split_non_manifold_edges->edges == 3);
  CHECK(r.split_non_manifold_edges->vertex_copies == 6);
  REQUIRE(r.pierced_faces);
  CHECK(r.pierced_faces->left_out_of_contact == std::vector<int>{5, 6, 7});
  CHECK(r.pierced_faces->opened == std::vector<int>{6});
  CHECK(r.pierced_faces->bones == std::vector<std::string>{"Hips-Spine"});
  CHECK(r.min_distance);
  REQUIRE(r.shape);
  CHECK(r.shape->surface_energy_per_area == 0.002);
  CHECK(r.loop_offsets == std::vector<double>{0.01, 0.03});
  REQUIRE(r.shrink);
  CHECK(r.shrink->depth == 0.04);
  REQUIRE(r.seconds.size() == 8);
  CHECK(r.seconds.back().seconds == 4.5);
  CHECK(r.peak_memory_mb == 81.0);
  CHECK(r.warnings == report.warnings);
}
