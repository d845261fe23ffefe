#include <cmath>
#include <map>
#include <utility>

#include <catch2/catch.hpp>

#include "core/mesh/boundary_loops.hpp"
#include "core/mesh/primitives.hpp"
#include "core/mesh/unique_edges.hpp"

using namespace gr;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// V − E + F.
long euler_characteristic(const TriangleMesh& mesh) {
  return static_cast<long>(mesh.vertices.rows()) -
         static_cast<long>(unique_edges(mesh.faces).rows()) + static_cast<long>(mesh.faces.rows());
}

/// Every directed edge at most once and, unless it lies on the boundary, its reverse once:
/// the faces are consistently oriented and the surface is manifold along its edges.
/// Returns the number of boundary (unpaired) directed edges, or -1 when an edge repeats.
long unpaired_directed_edges(const TriangleMesh& mesh) {
  std::map<std::pair<int, int>, int> count;
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) ++count[{mesh.faces(f, k), mesh.faces(f, (k + 1) % 3)}];
  long unpaired = 0;
  for (const auto& [edge, n] : count) {
    if (n != 1) return -1;
    unpaired += count.count({edge.second, edge.first}) == 0;
  }
  return unpaired;
}

/// The signed volume enclosed (positive for a closed, outward-oriented surface).
double signed_volume(const TriangleMesh& mesh) {
  double six_volume = 0.0;
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    six_volume +=
        mesh.vertices.row(mesh.faces(f, 0))
            .dot(mesh.vertices.row(mesh.faces(f, 1)).cross(mesh.vertices.row(mesh.faces(f, 2))));
  return six_volume / 6.0;
}

bool no_degenerate_face(const TriangleMesh& mesh) {
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    const Vector3d a = mesh.vertices.row(mesh.faces(f, 0)).transpose();
    const Vector3d b = mesh.vertices.row(mesh.faces(f, 1)).transpose();
    const Vector3d c = mesh.vertices.row(mesh.faces(f, 2)).transpose();
    if (!((b - a).cross(c - a).norm() > 0.0)) return false;
  }
  return true;
}

}  // namespace

TEST_CASE("uv_sphere is a closed, outward sphere of the stated layout", "[mesh][primitives]") {
  const int rings = GENERATE(2, 3, 9, 24);
  const int segments = GENERATE(3, 8, 48);
  const double radius = 0.7;
  const Vector3d center(0.1, -0.2, 0.3);
  CAPTURE(rings, segments);
  const TriangleMesh sphere = uv_sphere(radius, center, rings, segments);
  CHECK(sphere.vertices.rows() == 2 + (rings - 1) * segments);
  CHECK(sphere.faces.rows() == 2 * segments * (rings - 1));
  CHECK(euler_characteristic(sphere) == 2);
  CHECK(unpaired_directed_edges(sphere) == 0);
  CHECK(signed_volume(sphere) > 0.0);
  CHECK(no_degenerate_face(sphere));
  CHECK(sphere.vertices.row(0) == (center + Vector3d(0, 0, radius)).transpose());
  CHECK(sphere.vertices.row(1) == (center - Vector3d(0, 0, radius)).transpose());
  for (Eigen::Index v = 0; v < sphere.vertices.rows(); ++v)
    CHECK((sphere.vertices.row(v).transpose() - center).norm() == Approx(radius).epsilon(1e-14));
}

TEST_CASE("icosphere is closed, outward, on its sphere, with 20·4^s faces", "[mesh][primitives]") {
  const int subdivisions = GENERATE(0, 1, 2, 3);
  CAPTURE(subdivisions);
  const Vector3d center(1.0, 2.0, -0.5);
  const TriangleMesh sphere = icosphere(subdivisions, 2.0, center);
  const long four_s = 1L << (2 * subdivisions);
  CHECK(sphere.faces.rows() == 20 * four_s);
  CHECK(sphere.vertices.rows() == 10 * four_s + 2);
  CHECK(euler_characteristic(sphere) == 2);
  CHECK(unpaired_directed_edges(sphere) == 0);
  CHECK(no_degenerate_face(sphere));
  for (Eigen::Index v = 0; v < sphere.vertices.rows(); ++v)
    CHECK((sphere.vertices.row(v).transpose() - center).norm() == Approx(2.0).epsilon(1e-14));
  // Outward: the volume about the centre is positive and below the sphere's.
  TriangleMesh centred = sphere;
  centred.vertices.rowwise() -= center.transpose();
  const double volume = signed_volume(centred);
  CHECK(volume > 0.0);
  CHECK(volume < 4.0 / 3.0 * kPi * 8.0);
  CHECK(icosphere(subdivisions).vertices.rowwise().norm().maxCoeff() == Approx(1.0));
}

TEST_CASE("quad_grid numbers its points row by row and splits each cell the same way",
          "[mesh][primitives]") {
  const TriangleMesh grid =
      quad_grid(2, 3, false, [](int i, int j) { return Vector3d(j, i, 0.0); });
  REQUIRE(grid.vertices.rows() == 3 * 4);
  REQUIRE(grid.faces.rows() == 2 * 2 * 3);
  for (int i = 0; i <= 2; ++i)
    for (int j = 0; j <= 3; ++j) CHECK(grid.vertices.row(i * 4 + j) == RowVector3d(j, i, 0.0));
  // Cell (1, 2): the faces 2·(1·3 + 2) and the next.
  CHECK(grid.faces.row(10) == Eigen::RowVector3i(6, 7, 11));
  CHECK(grid.faces.row(11) == Eigen::RowVector3i(6, 11, 10));
  // Normals along ∂p/∂j × ∂p/∂i = x × y = +z.
  for (Eigen::Index f = 0; f < grid.faces.rows(); ++f) {
    const Vector3d a = grid.vertices.row(grid.faces(f, 0)).transpose();
    const Vector3d b = grid.vertices.row(grid.faces(f, 1)).transpose();
    const Vector3d c = grid.vertices.row(grid.faces(f, 2)).transpose();
    CHECK((b - a).cross(c - a).z() > 0.0);
  }
  CHECK(euler_characteristic(grid) == 1);  // a disc
  CHECK(unpaired_directed_edges(grid) == 2 * (2 + 3));
  CHECK(boundary_loops(grid.faces).size() == 1);
}

TEST_CASE("quad_grid wrapped around is a tube without a seam", "[mesh][primitives]") {
  const int columns = GENERATE(3, 7);
  CAPTURE(columns);
  int calls = 0;
  const TriangleMesh tube = quad_grid(2, columns, true, [&](int i, int j) {
    ++calls;
    CHECK(j < columns);
    const double angle = 2.0 * kPi * j / columns;
    return Vector3d(std::cos(angle), std::sin(angle), i);
  });
  CHECK(calls == 3 * columns);
  CHECK(tube.vertices.rows() == 3 * columns);
  CHECK(tube.faces.rows() == 2 * 2 * columns);
  CHECK(euler_characteristic(tube) == 0);
  CHECK(unpaired_directed_edges(tube) == 2 * columns);
  CHECK(boundary_loops(tube.faces).size() == 2);
}

TEST_CASE("open_cylinder is an outward tube with two boundary loops at its ends",
          "[mesh][primitives]") {
  const int rings = GENERATE(2, 3, 8);
  const int segments = GENERATE(3, 6, 24);
  CAPTURE(rings, segments);
  const double radius = 0.85, z0 = -0.5, z1 = 0.5;
  const TriangleMesh cylinder = open_cylinder(radius, z0, z1, rings, segments);
  CHECK(cylinder.vertices.rows() == rings * segments);
  CHECK(cylinder.faces.rows() == 2 * segments * (rings - 1));
  CHECK(euler_characteristic(cylinder) == 0);
  CHECK(unpaired_directed_edges(cylinder) == 2 * segments);
  CHECK(no_degenerate_face(cylinder));
  const auto loops = boundary_loops(cylinder.faces);
  REQUIRE(loops.size() == 2);
  for (const auto& loop : loops) {
    CHECK(loop.size() == static_cast<std::size_t>(segments));
    const double z = cylinder.vertices(loop.front(), 2);
    CHECK((z == z0 || z == z1));
    for (const int v : loop) CHECK(cylinder.vertices(v, 2) == z);
  }
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const RowVector3d p = cylinder.vertices.row(r * segments + s);
      CHECK(std::hypot(p.x(), p.y()) == Approx(radius).epsilon(1e-15));
      CHECK(p.z() == Approx(z0 + (z1 - z0) * r / (rings - 1)));
      CHECK(std::atan2(p.y(), p.x()) ==
            Approx(std::remainder(2.0 * kPi * s / segments, 2.0 * kPi)).margin(1e-12));
    }
  // Outward: each face's normal points away from the axis.
  for (Eigen::Index f = 0; f < cylinder.faces.rows(); ++f) {
    const Vector3d a = cylinder.vertices.row(cylinder.faces(f, 0)).transpose();
    const Vector3d b = cylinder.vertices.row(cylinder.faces(f, 1)).transpose();
    const Vector3d c = cylinder.vertices.row(cylinder.faces(f, 2)).transpose();
    const Vector3d centroid = (a + b + c) / 3.0;
    CHECK((b - a).cross(c - a).dot(Vector3d(centroid.x(), centroid.y(), 0.0)) > 0.0);
  }
}

TEST_CASE("box is a closed, outward box of the given half extents", "[mesh][primitives]") {
  const Vector3d half(0.3, 0.4, 0.8);
  const TriangleMesh cuboid = box(half);
  REQUIRE(cuboid.vertices.rows() == 8);
  REQUIRE(cuboid.faces.rows() == 12);
  CHECK(euler_characteristic(cuboid) == 2);
  CHECK(unpaired_directed_edges(cuboid) == 0);
  CHECK(no_degenerate_face(cuboid));
  CHECK(signed_volume(cuboid) == Approx(8.0 * half.prod()).epsilon(1e-15));
  CHECK(cuboid.vertices.colwise().maxCoeff() == half.transpose());
  CHECK(cuboid.vertices.colwise().minCoeff() == -half.transpose());
  for (int c = 0; c < 8; ++c)
    for (int k = 0; k < 3; ++k) CHECK(cuboid.vertices(c, k) == ((c >> k) & 1 ? half[k] : -half[k]));
  // Sides in the order −x, +x, −y, +y, −z, +z, two faces each.
  for (int side = 0; side < 6; ++side)
    for (int f = 2 * side; f < 2 * side + 2; ++f)
      for (int k = 0; k < 3; ++k) {
        CAPTURE(side, f, k);
        const double expected = side % 2 == 0 ? -half[side / 2] : half[side / 2];
        CHECK(cuboid.vertices(cuboid.faces(f, k), side / 2) == expected);
      }
}
