#include <algorithm>
#include <cmath>
#include <vector>

#include <catch2/catch.hpp>

#include "garment/repairs/untangle.hpp"
#include "scenes/synthetic/tangled_garments.hpp"
#include "validate/checks/self_intersections.hpp"

using namespace gr;

namespace {

std::vector<FacePair> crossings(const TriangleMesh& mesh) {
  return find_self_intersecting_face_pairs(mesh).pairs.pairs;
}

UntangleOptions options_for(const TangledGarment& t) {
  UntangleOptions options;
  options.separation = 1e-3;
  options.max_displacement = 2e-2;
  options.face_part = t.face_layer;
  if (!t.face_layer.empty()) {
    options.part_inside.resize(2, 2);
    options.part_inside << 0, 1, -1, 0;  // layer 0 inside layer 1
  }
  options.body_points = t.body_points;
  return options;
}

/// Largest move of a vertex farther than `radius` from every vertex of a crossing face.
double largest_move_away(const TriangleMesh& mesh, const std::vector<FacePair>& pairs,
                         const MatrixX3d& after, double radius) {
  std::vector<int> crossing;
  for (const FacePair& p : pairs)
    for (const int f : {p.first, p.second})
      for (int k = 0; k < 3; ++k) crossing.push_back(mesh.faces(f, k));
  double largest = 0.0;
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
    bool near = false;
    for (const int c : crossing)
      near = near || (mesh.vertices.row(v) - mesh.vertices.row(c)).norm() <= radius;
    if (!near) largest = std::max(largest, (after.row(v) - mesh.vertices.row(v)).norm());
  }
  return largest;
}

double radius_xy(const MatrixX3d& V, Eigen::Index v) { return std::hypot(V(v, 0), V(v, 1)); }

}  // namespace

TEST_CASE("Untangle: a fold pushed through a fold comes apart, locally", "[untangle]") {
  const double depth = GENERATE(0.002, 0.006);
  CAPTURE(depth);
  const TangledGarment t = make_fold_through_fold(depth);
  const std::vector<FacePair> pairs = crossings(t.garment);
  REQUIRE(pairs.size() > 10);
  const Untangled u = untangle_crossings(t.garment, pairs, options_for(t));
  CHECK(u.pairs_before == static_cast<int>(pairs.size()));
  CHECK(u.resolved == u.pairs_before);
  CHECK(u.left.empty());
  CHECK(u.remaining.empty());
  CHECK(crossings({u.vertices, t.garment.faces}).empty());
  // The dip goes up past the lower sheet (by its depth and the gap), and not much further.
  CHECK(u.max_displacement <= 3.0 * (depth + 1e-3));
  CHECK(u.max_displacement < options_for(t).max_displacement);
  CHECK(u.max_displacement >= depth);
  // Only around the dip: nothing four cells away from a crossing face moves (a push
  // spreads over three edge rings at most).
  CHECK(largest_move_away(t.garment, pairs, u.vertices, 4.0 / 24 + 1e-9) == 0.0);
  CHECK(moved_edge_change(t.garment, t.garment.vertices, u.vertices) < 0.2);
}

TEST_CASE("Untangle: a strap pressed through a band comes apart", "[untangle]") {
  const TangledGarment t = make_strap_through_band(0.004, false);
  const std::vector<FacePair> pairs = crossings(t.garment);
  REQUIRE(!pairs.empty());
  const Untangled u = untangle_crossings(t.garment, pairs, options_for(t));
  CHECK(u.resolved == u.pairs_before);
  CHECK(crossings({u.vertices, t.garment.faces}).empty());
  CHECK(u.max_displacement <= 2e-2);
}

TEST_CASE("Untangle: layers crossing at a hem part inner in, outer out", "[untangle][layers]") {
  const TangledGarment t = make_layers_crossing_at_hem(0.004);
  const std::vector<FacePair> pairs = crossings(t.garment);
  REQUIRE(!pairs.empty());
  for (const FacePair& p : pairs)  // every crossing is between the two layers
    CHECK(t.face_layer[static_cast<std::size_t>(p.first)] !=
          t.face_layer[static_cast<std::size_t>(p.second)]);
  const Untangled u = untangle_crossings(t.garment, pairs, options_for(t));
  CHECK(u.resolved == u.pairs_before);
  CHECK(crossings({u.vertices, t.garment.faces}).empty());
  // The outer layer's tucked hem went out past the inner layer, and the inner layer in:
  // summed over each layer, the moves away from the axis.
  const auto inner_vertices = static_cast<Eigen::Index>(13 * 40);  // 13 rings of 40
  const auto outward_moves = [&](const MatrixX3d& after) {
    std::array<double, 2> sum{0.0, 0.0};
    for (Eigen::Index v = 0; v < t.garment.vertices.rows(); ++v)
      sum[v < inner_vertices ? 0 : 1] += radius_xy(after, v) - radius_xy(t.garment.vertices, v);
    return sum;
  };
  const std::array<double, 2> moved = outward_moves(u.vertices);
  CAPTURE(moved[0], moved[1]);
  CHECK(moved[0] < 0.0);
  CHECK(moved[1] > 0.0);
}

TEST_CASE("Untangle: an eyelet sunk through a sheet comes out whole", "[untangle]") {
  const double depth = GENERATE(0.003, 0.008);
  const bool ordered = GENERATE(false, true);
  CAPTURE(depth, ordered);
  const TangledGarment t = make_eyelet_through_sheet(depth);
  const std::vector<FacePair> pairs = crossings(t.garment);
  REQUIRE(pairs.size() >= 8);
  UntangleOptions options = options_for(t);
  double gap = options.separation;
  if (ordered) {
    // The eyelet a layer over the sheet: the gap between layers applies.
    options.face_part.assign(static_cast<std::size_t>(t.garment.faces.rows()), 0);
    for (std::size_t f = 2 * 24 * 24; f < options.face_part.size(); ++f) options.face_part[f] = 1;
    options.part_inside.resize(2, 2);
    options.part_inside << 0, 1, -1, 0;
    options.part_layer = {0, 1};
    options.layer_separation = gap = 4e-3;
  }
  const Untangled u = untangle_crossings(t.garment, pairs, options);
  CHECK(u.resolved == u.pairs_before);
  CHECK(u.remaining.empty());
  CHECK(crossings({u.vertices, t.garment.faces}).empty());
  // The eyelet (the last 16 vertices) moved as one, out of the sheet by its depth and the
  // gap; the sheet stayed.
  const Eigen::Index sheet = t.garment.vertices.rows() - 16;
  CHECK(u.vertices.topRows(sheet) == t.garment.vertices.topRows(sheet));
  const Vector3d shift = (u.vertices.row(sheet) - t.garment.vertices.row(sheet)).transpose();
  for (Eigen::Index v = sheet; v < u.vertices.rows(); ++v)
    CHECK((u.vertices.row(v) - t.garment.vertices.row(v) - shift.transpose()).norm() < 1e-12);
  CHECK((shift - Vector3d(0.0, 0.0, depth + gap)).norm() < 1e-12);
  CHECK(moved_edge_change(t.garment, t.garment.vertices, u.vertices) < 1e-12);
}

TEST_CASE("Untangle: a strap right through a band wall is left, with its reason", "[untangle]") {
  const TangledGarment t = make_strap_through_band(0.0, true);
  const std::vector<FacePair> pairs = crossings(t.garment);
  REQUIRE(!pairs.empty());
  const UntangleOptions options = options_for(t);
  const Untangled u = untangle_crossings(t.garment, pairs, options);
  // The strap still crosses the wall (the crossing may have moved to other faces).
  CHECK(!u.remaining.empty());
  CHECK(!u.left.empty());
  CHECK(static_cast<int>(u.left.size()) + u.resolved == u.pairs_before + u.added);
  for (const LeftCrossing& left : u.left)
    CHECK((left.reason == TangleLeft::kBudget || left.reason == TangleLeft::kStalled));
  CHECK(std::count_if(u.left.begin(), u.left.end(),
                      [](const LeftCrossing& left) { return left.made; }) == u.added);
  // What is left still crosses, as listed, and no vertex went beyond the budget.
  const std::vector<FacePair> after = crossings({u.vertices, t.garment.faces});
  CHECK(after.size() == u.remaining.size());
  CHECK(u.max_displacement <= options.max_displacement + 1e-12);
  // A push is kept only where it made fewer or shallower crossings: never more in all.
  CHECK(after.size() <= pairs.size());
}

TEST_CASE("Untangle: pinned vertices stay, and a garment crossing nothing is unchanged",
          "[untangle]") {
  const TangledGarment t = make_fold_through_fold(0.004);
  SECTION("nothing crossing") {
    TriangleMesh lower{t.garment.vertices, t.garment.faces.topRows(2 * 24 * 24)};
    const Untangled u = untangle_crossings(lower, {}, options_for(t));
    CHECK(u.vertices == lower.vertices);
    CHECK(u.pairs_before == 0);
    CHECK(u.moved_vertices == 0);
  }
  SECTION("the lower sheet pinned: the dip alone goes up") {
    UntangleOptions options = options_for(t);
    options.pinned.assign(static_cast<std::size_t>(t.garment.vertices.rows()), 0);
    std::fill(options.pinned.begin(), options.pinned.begin() + 25 * 25, 1);
    const std::vector<FacePair> pairs = crossings(t.garment);
    const Untangled u = untangle_crossings(t.garment, pairs, options);
    CHECK(u.resolved == u.pairs_before);
    CHECK(u.vertices.topRows(25 * 25) == t.garment.vertices.topRows(25 * 25));
  }
  SECTION("bad options") {
    UntangleOptions options = options_for(t);
    options.pinned.assign(3, 0);
    CHECK_THROWS_AS(untangle_crossings(t.garment, crossings(t.garment), options),
                    std::invalid_argument);
  }
}

TEST_CASE("Untangle: the report's share and edge change", "[untangle]") {
  UntangleReport report;
  CHECK(resolved_share(report) == 1.0);
  report.pairs = 8;
  report.resolved = 6;
  report.remaining = 2;
  CHECK(resolved_share(report) == Approx(0.75));
  report.remaining = 3;  // one made by the untangle counts against it
  CHECK(resolved_share(report) == Approx(0.625));
  const nlohmann::json json = to_json(report);
  CHECK(json["resolved_share"].get<double>() == Approx(0.625));
  TriangleMesh triangle;
  triangle.vertices.resize(3, 3);
  triangle.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  triangle.faces.resize(1, 3);
  triangle.faces << 0, 1, 2;
  MatrixX3d moved = triangle.vertices;
  moved(1, 0) = 2.0;  // edge 0-1 doubles, 1-2 grows to sqrt(5)
  CHECK(moved_edge_change(triangle, triangle.vertices, moved) ==
        Approx((1.0 + (std::sqrt(5.0) / std::sqrt(2.0) - 1.0)) / 2.0));
  CHECK(moved_edge_change(triangle, triangle.vertices, triangle.vertices) == 0.0);
}
