#include <cmath>
#include <numeric>
#include <set>

#include <catch2/catch.hpp>

#include "../test_shapes.hpp"
#include "core/candidates/fold_free_regions.hpp"
#include "core/mesh/unique_edges.hpp"

using gr::MatrixX3d;
using gr::MatrixX3i;
using Region = gr::GarmentRegions::Region;

namespace {

gr::GarmentRegions regions_of(const gr::TriangleMesh& mesh, int max_leaf_faces) {
  return gr::build_garment_regions(mesh.faces, gr::unique_edges(mesh.faces), mesh.vertices,
                                   max_leaf_faces);
}

/// A flat-ish strip between radii 1 and 1.5 around the z axis, from angle 0 to `end`, rising
/// by `pitch` per radian: normals near +z. Past one turn it lies over itself in projection.
gr::TriangleMesh ring_strip(double end, int segments, double pitch) {
  return gr::quad_grid(segments, 1, false, [&](int k, int side) {
    const double angle = end * k / segments, radius = side == 0 ? 1.0 : 1.5;
    return gr::Vector3d(radius * std::cos(angle), radius * std::sin(angle), pitch * angle);
  });
}

const Region& only_root(const gr::GarmentRegions& regions) {
  REQUIRE(regions.roots.size() == 1);
  return regions.regions[static_cast<std::size_t>(regions.roots.front())];
}

}  // namespace

TEST_CASE("garment regions: leaves partition the faces and every join covers its two parts",
          "[candidates][fold_free]") {
  const gr::TriangleMesh grid = gr::test::curved_grid(11, 0.0);
  const gr::GarmentRegions regions = regions_of(grid, 16);
  const auto face_count = static_cast<std::size_t>(grid.faces.rows());

  std::vector<int> seen(face_count, 0);
  for (std::size_t leaf = 0; leaf < regions.leaves.size(); ++leaf) {
    const Region& region = regions.regions[static_cast<std::size_t>(regions.leaves[leaf])];
    CHECK(region.leaf == static_cast<int>(leaf));
    CHECK(region.faces.size() <= 16);
    for (int f : region.faces) {
      ++seen[static_cast<std::size_t>(f)];
      CHECK(regions.face_leaf[static_cast<std::size_t>(f)] == static_cast<int>(leaf));
    }
  }
  CHECK(std::all_of(seen.begin(), seen.end(), [](int n) { return n == 1; }));
  for (std::size_t r = 0; r < regions.regions.size(); ++r) {
    const Region& region = regions.regions[r];
    if (region.leaf >= 0) continue;
    for (int child : region.children) CHECK(static_cast<std::size_t>(child) < r);  // children first
    const std::size_t parts =
        regions.regions[static_cast<std::size_t>(region.children[0])].faces.size() +
        regions.regions[static_cast<std::size_t>(region.children[1])].faces.size();
    CHECK(region.faces.size() == parts);
  }
  const Region& root = only_root(regions);
  CHECK(root.faces.size() == face_count);
  CHECK(root.disk);
  CHECK(root.boundary.size() == 40);  // the grid's rim
  for (std::size_t v = 0; v < regions.vertex_leaf.size(); ++v) CHECK(regions.vertex_leaf[v] >= 0);
  for (int leaf : regions.edge_leaf) CHECK(leaf >= 0);
}

TEST_CASE("fold free: a flat sheet is, and a clearance above its face heights is not met",
          "[candidates][fold_free]") {
  const gr::TriangleMesh grid = gr::test::curved_grid(11, 0.0);
  const gr::GarmentRegions regions = regions_of(grid, 16);
  const Region& root = only_root(regions);
  CHECK(gr::stays_fold_free(root, grid.faces, grid.vertices, grid.vertices));
  // Cells of 0.1: the smallest face height is 0.1 / sqrt(2).
  CHECK(gr::stays_fold_free(root, grid.faces, grid.vertices, grid.vertices, 0.05));
  CHECK_FALSE(gr::stays_fold_free(root, grid.faces, grid.vertices, grid.vertices, 0.08));
  // A gently curved sheet, moved and bent a little more, still is.
  const gr::TriangleMesh curved = gr::test::curved_grid(11, 0.2);
  MatrixX3d moved = gr::test::curved_grid(11, 0.3).vertices;
  moved.col(0).array() += 5.0;
  const gr::GarmentRegions curved_regions = regions_of(curved, 16);
  CHECK(gr::stays_fold_free(only_root(curved_regions), curved.faces, curved.vertices, moved, 0.01));
}

TEST_CASE("fold free: folding a sheet over onto itself is not, its resting half is",
          "[candidates][fold_free]") {
  const gr::TriangleMesh grid = gr::test::curved_grid(11, 0.0);
  const gr::GarmentRegions regions = regions_of(grid, 16);
  MatrixX3d folded = grid.vertices;
  const double angle = 3.0;  // nearly flat onto the other half
  for (Eigen::Index v = 0; v < folded.rows(); ++v) {
    const double x = grid.vertices(v, 0) - 0.5;
    if (x <= 0.0) continue;
    folded(v, 0) = 0.5 + x * std::cos(angle);
    folded(v, 2) = x * std::sin(angle);
  }
  CHECK_FALSE(gr::stays_fold_free(only_root(regions), grid.faces, grid.vertices, folded));
  int resting = 0;
  for (int leaf_region : regions.leaves) {
    const Region& leaf = regions.regions[static_cast<std::size_t>(leaf_region)];
    const bool still = std::all_of(leaf.vertices.begin(), leaf.vertices.end(),
                                   [&](int v) { return grid.vertices(v, 0) <= 0.5; });
    if (!still) continue;
    ++resting;
    CHECK(gr::stays_fold_free(leaf, grid.faces, grid.vertices, folded));
  }
  CHECK(resting > 0);
}

TEST_CASE(
    "fold free: a strip lying over itself in projection is not, though every normal points up",
    "[candidates][fold_free]") {
  const gr::TriangleMesh spiral = ring_strip(3.0 * M_PI, 60, 0.02);
  const gr::GarmentRegions spiral_regions = regions_of(spiral, 1000);
  const Region& coiled = only_root(spiral_regions);
  REQUIRE(coiled.disk);
  CHECK_FALSE(gr::stays_fold_free(coiled, spiral.faces, spiral.vertices, spiral.vertices));
  const gr::TriangleMesh arc = ring_strip(1.5 * M_PI, 30, 0.02);
  const gr::GarmentRegions arc_regions = regions_of(arc, 1000);
  CHECK(gr::stays_fold_free(only_root(arc_regions), arc.faces, arc.vertices, arc.vertices));
}

TEST_CASE("fold free: the boundary keeps the clearance from itself across a gap",
          "[candidates][fold_free]") {
  // A C-shaped ring whose two ends are about 0.05 apart; its faces are far thicker.
  const gr::TriangleMesh ring = ring_strip(2.0 * M_PI - 0.05, 40, 0.0);
  const gr::GarmentRegions ring_regions = regions_of(ring, 1000);
  const Region& c_shape = only_root(ring_regions);
  CHECK(gr::stays_fold_free(c_shape, ring.faces, ring.vertices, ring.vertices, 0.02));
  CHECK_FALSE(gr::stays_fold_free(c_shape, ring.faces, ring.vertices, ring.vertices, 0.1));
  // Closing the gap along a motion: the ends would meet.
  const gr::TriangleMesh closed = ring_strip(2.0 * M_PI + 0.05, 40, 0.0);
  CHECK_FALSE(gr::stays_fold_free(c_shape, ring.faces, ring.vertices, closed.vertices));
}

TEST_CASE("fold free: a face that turns over and back within one motion is caught",
          "[candidates][fold_free]") {
  // p1 = (1, 3τ), p2 = (3 - 3τ, 1): the orientation 1 - 9τ(1 - τ) is positive at both ends
  // and negative in the middle.
  gr::TriangleMesh face;
  face.vertices.resize(3, 3);
  face.vertices << 0, 0, 0, 1, 0, 0, 3, 1, 0;
  face.faces.resize(1, 3);
  face.faces << 0, 1, 2;
  MatrixX3d end = face.vertices;
  end.row(1) << 1, 3, 0;
  end.row(2) << 0, 1, 0;
  const gr::GarmentRegions face_regions = regions_of(face, 4);
  const Region& single = only_root(face_regions);
  CHECK(gr::stays_fold_free(single, face.faces, face.vertices, face.vertices));
  CHECK(gr::stays_fold_free(single, face.faces, end, end));
  CHECK_FALSE(gr::stays_fold_free(single, face.faces, face.vertices, end));
}

TEST_CASE("garment regions: pieces, holes and inconsistent orientation",
          "[candidates][fold_free]") {
  // Two separate sheets: two roots. A sheet with a hole: not a disk at the top.
  gr::TriangleMesh two = gr::test::curved_grid(5, 0.0);
  const auto faces = two.faces.rows(), vertices = two.vertices.rows();
  two.vertices.conservativeResize(2 * vertices, 3);
  two.vertices.bottomRows(vertices) = two.vertices.topRows(vertices);
  two.vertices.bottomRows(vertices).col(2).array() += 1.0;
  two.faces.conservativeResize(2 * faces, 3);
  two.faces.bottomRows(faces) = two.faces.topRows(faces).array() + static_cast<int>(vertices);
  CHECK(regions_of(two, 8).roots.size() == 2);

  const gr::TriangleMesh ring = ring_strip(2.0 * M_PI, 24, 0.0);
  gr::TriangleMesh annulus = ring;  // close the ring: last column joins the first
  for (Eigen::Index f = 0; f < annulus.faces.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (annulus.faces(f, k) >= 48) annulus.faces(f, k) -= 48;
  const gr::GarmentRegions closed = regions_of(annulus, 1000);
  CHECK_FALSE(only_root(closed).disk);
  CHECK_FALSE(
      gr::stays_fold_free(only_root(closed), annulus.faces, annulus.vertices, annulus.vertices));

  gr::TriangleMesh flipped = gr::test::curved_grid(5, 0.0);
  std::swap(flipped.faces(3, 1), flipped.faces(3, 2));  // one face turned the other way
  const gr::GarmentRegions mixed = regions_of(flipped, 1000);
  for (const Region& region : mixed.regions)
    if (std::find(region.faces.begin(), region.faces.end(), 3) != region.faces.end() &&
        region.faces.size() > 1)
      CHECK_FALSE(gr::stays_fold_free(region, flipped.faces, flipped.vertices, flipped.vertices));
}
