#include <catch2/catch.hpp>

#include <vector>

#include "core/mesh/pieces.hpp"

using namespace gr;

TEST_CASE("pieces: each vertex takes the smallest vertex id of its piece", "[mesh]") {
  // Vertices 0..3: a quad of two faces; 4: in no face; 5..9: three faces given from the
  // highest ids down, vertex 6 joined by the last one.
  TriangleMesh mesh;
  mesh.vertices = MatrixX3d::Zero(10, 3);
  mesh.faces.resize(5, 3);
  mesh.faces << 0, 1, 2,  //
      2, 1, 3,            //
      9, 8, 7,            //
      8, 9, 5,            //
      5, 6, 9;
  const std::vector<int> pieces = vertex_pieces(mesh);
  CHECK(pieces == std::vector<int>{0, 0, 0, 0, 4, 5, 5, 5, 5, 5});
}

TEST_CASE("pieces: a mesh without faces is a piece per vertex", "[mesh]") {
  TriangleMesh mesh;
  mesh.vertices = MatrixX3d::Zero(3, 3);
  mesh.faces.resize(0, 3);
  CHECK(vertex_pieces(mesh) == std::vector<int>{0, 1, 2});
}
