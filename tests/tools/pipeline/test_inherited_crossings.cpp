#include <catch2/catch.hpp>

#include "tools/pipeline/inherited_crossings.hpp"
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
