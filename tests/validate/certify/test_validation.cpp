#include <utility>
#include <vector>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "core/common/errors.hpp"
#include "validate/certify/validation.hpp"
#include "validate/report/validation_report.hpp"
#include "validate/validate_test_meshes.hpp"

using gr::test::concatenate;
using gr::test::make_mesh;
using gr::test::triangle;

namespace {

/// Far from every layer: the layers are checked against each other only.
const gr::TriangleMesh kAvatar = triangle({10, 10, 10}, {11, 10, 10}, {10, 11, 10});

/// The inner layer: two flat faces at z = 0.5, face 0 over x in [0, 1], face 1 over
/// x in [3, 4].
const gr::TriangleMesh kInner =
    make_mesh({{0, 0, 0.5}, {1, 0, 0.5}, {0, 1, 0.5}, {3, 0, 0.5}, {4, 0, 0.5}, {3, 1, 0.5}},
              {{0, 1, 2}, {3, 4, 5}});

/// A small slanted face at (x, 0.2) spanning z in [low, low + 0.2]: through the inner
/// layer's plane when low = 0.4, above it when low = 0.8.
gr::TriangleMesh slanted(double x, double low) {
  return triangle({x, 0.2, low}, {x + 0.1, 0.2, low + 0.2}, {x, 0.3, low + 0.2});
}

/// The outer layer: face 0 over the inner layer's face 0, face 1 over its face 1, each
/// through it or not.
gr::TriangleMesh outer(bool face_0_crosses, bool face_1_crosses) {
  return concatenate(slanted(0.2, face_0_crosses ? 0.4 : 0.8),
                     slanted(3.2, face_1_crosses ? 0.4 : 0.8));
}

gr::ValidationOptions inheriting(std::vector<gr::FacePair> faces) {
  gr::ValidationOptions options;
  options.inherited_layer_pairs.push_back({0, 1, std::move(faces)});
  return options;
}

}  // namespace

TEST_CASE("layers crossing where their input did are counted apart", "[validate][inherited]") {
  const gr::TriangleMesh tucked = outer(true, false);  // crosses at (0, 0) only

  SECTION("without the option the crossing fails") {
    const gr::ValidationResult r = gr::validate_meshes({kInner, tucked}, kAvatar, {});
    REQUIRE(r.garment_pairs.size() == 1);
    CHECK(r.garment_pairs[0].intersections.count == 1);
    CHECK(r.garment_pairs[0].inherited_intersections == 0);
    CHECK(r.intersection_count() == 1);
    CHECK_FALSE(r.certified());
  }

  SECTION("the inherited crossing passes, counted once") {
    const gr::ValidationResult r =
        gr::validate_meshes({kInner, tucked}, kAvatar, inheriting({{0, 0}}));
    REQUIRE(r.garment_pairs.size() == 1);
    const gr::GarmentPairFindings& p = r.garment_pairs[0];
    CHECK(p.intersections.count == 0);
    CHECK(p.intersections.pairs.empty());
    CHECK(p.inherited_intersections == 1);
    // They still touch there: clearance 0 at the inherited pair, without nearest points.
    CHECK(p.clearance.distance == 0.0);
    CHECK(p.clearance.first_face == 0);
    CHECK(p.clearance.second_face == 0);
    CHECK_FALSE(p.clearance_has_points);
    CHECK(r.totals().garment_garment_intersections == 0);
    CHECK(r.totals().inherited_layer_intersections == 1);
    CHECK(r.intersection_count() == 0);
    CHECK(r.certified());
  }

  SECTION("pairs are (face of first, face of second), in that order") {
    // Outer face 1 crosses inner face 0; outer face 0 is clear above inner face 1.
    const gr::TriangleMesh swapped = concatenate(slanted(3.2, 0.8), slanted(0.2, 0.4));
    const gr::ValidationResult reversed =
        gr::validate_meshes({kInner, swapped}, kAvatar, inheriting({{1, 0}}));
    CHECK(reversed.garment_pairs[0].intersections.count == 1);
    CHECK(reversed.garment_pairs[0].inherited_intersections == 0);
    CHECK_FALSE(reversed.certified());
    const gr::ValidationResult ordered =
        gr::validate_meshes({kInner, swapped}, kAvatar, inheriting({{0, 1}}));
    CHECK(ordered.garment_pairs[0].inherited_intersections == 1);
    CHECK(ordered.certified());
  }
}

TEST_CASE("a new crossing between layers fails beside an inherited one", "[validate][inherited]") {
  const gr::ValidationResult r =
      gr::validate_meshes({kInner, outer(true, true)}, kAvatar, inheriting({{0, 0}}));
  REQUIRE(r.garment_pairs.size() == 1);
  const gr::GarmentPairFindings& p = r.garment_pairs[0];
  REQUIRE(p.intersections.count == 1);
  REQUIRE(p.intersections.pairs.size() == 1);
  CHECK(p.intersections.pairs[0].first == 1);
  CHECK(p.intersections.pairs[0].second == 1);
  CHECK(p.inherited_intersections == 1);
  CHECK(p.clearance.distance == 0.0);
  CHECK(r.totals().garment_garment_intersections == 1);
  CHECK(r.totals().inherited_layer_intersections == 1);
  CHECK_FALSE(r.certified());
}

TEST_CASE("an inherited layer pair that no longer crosses counts 0", "[validate][inherited]") {
  const gr::ValidationResult r =
      gr::validate_meshes({kInner, outer(false, false)}, kAvatar, inheriting({{0, 0}, {1, 1}}));
  REQUIRE(r.garment_pairs.size() == 1);
  const gr::GarmentPairFindings& p = r.garment_pairs[0];
  CHECK(p.intersections.count == 0);
  CHECK(p.inherited_intersections == 0);
  CHECK(p.clearance.distance == Approx(0.3));
  CHECK(p.clearance_has_points);
  CHECK(r.totals().inherited_layer_intersections == 0);
  CHECK(r.certified());
}

TEST_CASE("inherited layer pairs belong to the garment pair they name", "[validate][inherited]") {
  // Garments 1 and 2 both cross garment 0 at (0, 0); only the pair (0, 1) inherited it.
  const gr::TriangleMesh tucked = outer(true, false);
  const gr::TriangleMesh shifted = concatenate(slanted(0.5, 0.4), slanted(3.2, 5.0));
  const gr::ValidationResult r =
      gr::validate_meshes({kInner, tucked, shifted}, kAvatar, inheriting({{0, 0}}));
  REQUIRE(r.garment_pairs.size() == 3);
  CHECK(r.garment_pairs[0].second == 1);
  CHECK(r.garment_pairs[0].intersections.count == 0);
  CHECK(r.garment_pairs[0].inherited_intersections == 1);
  CHECK(r.garment_pairs[1].second == 2);
  CHECK(r.garment_pairs[1].intersections.count == 1);
  CHECK(r.garment_pairs[1].inherited_intersections == 0);
  CHECK_FALSE(r.certified());
}

TEST_CASE("an inherited layer entry must name two garments, first < second",
          "[validate][inherited]") {
  const std::vector<gr::TriangleMesh> layers = {kInner, outer(true, false)};
  gr::ValidationOptions options;
  using Garments = std::pair<int, int>;
  const Garments entry = GENERATE(Garments{1, 0}, Garments{0, 0}, Garments{-1, 1}, Garments{0, 2});
  CAPTURE(entry.first, entry.second);
  options.inherited_layer_pairs.push_back({entry.first, entry.second, {{0, 0}}});
  CHECK_THROWS_AS(gr::validate_meshes(layers, kAvatar, options), gr::InputError);
}

TEST_CASE("the report counts inherited layer crossings apart", "[validate][inherited][report]") {
  gr::Validation v;
  v.garments.resize(2);
  v.garments[0].mesh = kInner;
  v.garments[1].mesh = outer(true, true);
  v.avatar.mesh = kAvatar;
  v.options = inheriting({{0, 0}});
  v.result = gr::validate_meshes({v.garments[0].mesh, v.garments[1].mesh}, kAvatar, v.options);
  const nlohmann::ordered_json report = gr::validation_report(v);
  CHECK(report["counts"]["garment_garment_intersections"] == 1);
  CHECK(report["counts"]["inherited_layer_intersections"] == 1);
  const auto& pair = report["garment_pairs"][0];
  CHECK(pair["intersections"]["count"] == 1);
  REQUIRE(pair["intersections"]["pairs"].size() == 1);
  CHECK(pair["intersections"]["pairs"][0] == nlohmann::ordered_json::array({1, 1}));
  CHECK(pair["inherited_intersections"] == 1);
  std::size_t layer_errors = 0;
  for (const auto& message : report["issues"]["messages"])
    if (message["code"] == "GARMENT_GARMENT_INTERSECTION") ++layer_errors;
  CHECK(layer_errors == 1);
  CHECK(report["certified"] == false);
  CHECK_THAT(gr::validation_summary(v), Catch::Contains("1 inherited garment-garment pairs"));

  v.garments[1].mesh = outer(true, false);
  v.result = gr::validate_meshes({v.garments[0].mesh, v.garments[1].mesh}, kAvatar, v.options);
  const nlohmann::ordered_json passing = gr::validation_report(v);
  CHECK(passing["counts"]["garment_garment_intersections"] == 0);
  CHECK(passing["counts"]["inherited_layer_intersections"] == 1);
  CHECK(passing["garment_pairs"][0]["inherited_intersections"] == 1);
  CHECK(passing["issues"]["num_errors"] == 0);
  CHECK(passing["certified"] == true);
  CHECK(gr::validation_summary(v).rfind("certified", 0) == 0);
}
