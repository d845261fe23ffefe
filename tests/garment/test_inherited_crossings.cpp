#include <vector>

#include <catch2/catch.hpp>

#include "garment/repairs/inherited_crossings.hpp"
#include "validate/checks/self_intersections.hpp"

using namespace gr;

namespace {

/// Two squares crossing at right angles (a strap through a sheet), and a triangle far off.
TriangleMesh strap_through_sheet() {
  TriangleMesh mesh;
  mesh.vertices.resize(11, 3);
  mesh.vertices << -1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0,  // the sheet, z = 0
      0, -0.5, -1, 0, 0.5, -1, 0, 0.5, 1, 0, -0.5, 1,       // the strap, x = 0
      5, 5, 5, 6, 5, 5, 5, 6, 5;                            // far off
  mesh.faces.resize(5, 3);
  mesh.faces << 0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7, 8, 9, 10;
  return mesh;
}

}  // namespace

TEST_CASE("Inherited crossings: both sides of a crossing share one tangle", "[inherited]") {
  const TriangleMesh mesh = strap_through_sheet();
  const SelfIntersections self = find_self_intersecting_face_pairs(mesh);
  REQUIRE(self.pairs.count > 0);
  const InheritedCrossings crossings = tangles_of(mesh, self.pairs.pairs, 2);
  CHECK(crossings.pairs.size() == self.pairs.count);
  CHECK(crossings.tangle_count == 1);
  CHECK(crossings.tangled_vertices == 8);
  for (int v = 0; v < 8; ++v) CHECK(crossings.tangles[static_cast<std::size_t>(v)] == 0);
  for (int v = 8; v < 11; ++v) CHECK(crossings.tangles[static_cast<std::size_t>(v)] == -1);
  CHECK(tangles_of(mesh, {}, 2).tangles.empty());
}

TEST_CASE("Inherited crossings: the neighbourhood reaches the rings asked for", "[inherited]") {
  // A strip of squares; only its first face crosses a strap.
  TriangleMesh mesh;
  const int columns = 6;
  mesh.vertices.resize(2 * (columns + 1) + 3, 3);
  for (int i = 0; i <= columns; ++i) {
    mesh.vertices.row(2 * i) << i, 0, 0;
    mesh.vertices.row(2 * i + 1) << i, 1, 0;
  }
  const int s = 2 * (columns + 1);
  mesh.vertices.row(s) << 0.3, 0.3, -1;
  mesh.vertices.row(s + 1) << 0.3, 0.6, 1;
  mesh.vertices.row(s + 2) << 0.6, 0.3, 1;
  mesh.faces.resize(2 * columns + 1, 3);
  for (int i = 0; i < columns; ++i) {
    mesh.faces.row(2 * i) << 2 * i, 2 * i + 2, 2 * i + 3;
    mesh.faces.row(2 * i + 1) << 2 * i, 2 * i + 3, 2 * i + 1;
  }
  mesh.faces.row(2 * columns) << s, s + 1, s + 2;
  const SelfIntersections self = find_self_intersecting_face_pairs(mesh);
  REQUIRE(self.pairs.count > 0);
  const InheritedCrossings one = tangles_of(mesh, self.pairs.pairs, 1);
  const InheritedCrossings three = tangles_of(mesh, self.pairs.pairs, 3);
  CHECK(one.tangled_vertices < three.tangled_vertices);
  // The strip's far end stays outside.
  CHECK(three.tangles[static_cast<std::size_t>(2 * columns)] == -1);
  CHECK(three.tangles[static_cast<std::size_t>(s)] == three.tangles[0]);
}

TEST_CASE("Inherited crossings: a piece through another is attached to it", "[inherited]") {
  const TriangleMesh mesh = strap_through_sheet();
  const SelfIntersections self = find_self_intersecting_face_pairs(mesh);
  int pieces = 0;
  const std::vector<Attachment> attachments =
      attach_crossing_pieces(mesh, self.pairs.pairs, {}, pieces);
  CHECK(pieces == 1);
  // The strap (2 faces) follows the sheet (2 faces; ties go to the lower piece): either way
  // one piece's four vertices, each on a triangle of the other piece.
  REQUIRE(attachments.size() == 4);
  for (const Attachment& a : attachments) {
    const bool strap = a.vertex >= 4 && a.vertex < 8;
    for (const int corner : a.triangle) CHECK((corner >= 4 && corner < 8) != strap);
    const Vector3d centroid = (mesh.vertices.row(a.triangle[0]) + mesh.vertices.row(a.triangle[1]) +
                               mesh.vertices.row(a.triangle[2]))
                                  .transpose() /
                              3.0;
    CHECK((mesh.vertices.row(a.vertex).transpose() - centroid - a.offset).norm() < 1e-12);
  }
  // Crossings within one piece attach nothing.
  CHECK(attach_crossing_pieces(mesh, {}, {}, pieces).empty());
  // Nor do crossings between two layers of an outfit: the strap (faces 2 and 3) is a
  // garment of its own.
  CHECK(attach_crossing_pieces(mesh, self.pairs.pairs, {0, 0, 1, 1, 1}, pieces).empty());
  CHECK(pieces == 0);
  CHECK(attach_crossing_pieces(mesh, self.pairs.pairs, {1, 1, 1, 1, 1}, pieces).size() == 4);
  CHECK(pieces == 1);
}
