#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Geometry>

#include "core/mesh/primitives.hpp"
#include "core/mesh/subdivision.hpp"
#include "garment/outfit_meshes.hpp"
#include "garment/proxy/coarse_proxy.hpp"

using namespace gr;

namespace {

/// A sleeve of radius 0.5 (`rings` × `segments`) around a capsule of radius 0.3 whose
/// shrunk copy has radius `shrunk_radius`.
GarmentScene sleeve_scene(int rings, int segments, double shrunk_radius) {
  GarmentScene scene;
  scene.garment = open_cylinder(0.5, -0.6, 0.6, rings, segments);
  scene.avatar = test::capsule_body(0.3, 1.0);
  scene.shrunk_avatar = scene.avatar.vertices;
  scene.shrunk_avatar.leftCols(2) *= shrunk_radius / 0.3;
  return scene;
}

}  // namespace

TEST_CASE("coarse proxy: a fine mesh carried by a coarse one at rest and moved rigidly",
          "[pipeline][coarse_to_fine]") {
  const TriangleMesh coarse = open_cylinder(1.0, -1.0, 1.0, 5, 12);
  // Finer and a little larger, so that its vertices lie off the coarse surface.
  const TriangleMesh fine = open_cylinder(1.02, -0.9, 0.9, 17, 48);
  const SurfaceEmbedding embedding(coarse, fine.vertices);
  CHECK(embedding.max_offset() > 0.01);
  CHECK(embedding.max_offset() < 0.1);
  CHECK((embedding.carry(coarse.vertices) - fine.vertices).cwiseAbs().maxCoeff() < 1e-12);

  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, 2.0, -0.5).normalized()).toRotationMatrix();
  const Eigen::RowVector3d shift(0.3, -1.0, 2.5);
  const MatrixX3d moved_coarse = (coarse.vertices * rotation.transpose()).rowwise() + shift;
  const MatrixX3d moved_fine = (fine.vertices * rotation.transpose()).rowwise() + shift;
  CHECK((embedding.carry(moved_coarse) - moved_fine).cwiseAbs().maxCoeff() < 1e-12);

  // Stretched along its axis, the points follow their faces.
  MatrixX3d stretched = coarse.vertices;
  stretched.col(2) *= 2.0;
  const MatrixX3d carried = embedding.carry(stretched);
  CHECK(carried.col(2).maxCoeff() == Approx(1.8).epsilon(1e-9));
}

TEST_CASE("coarse proxy: a dense sleeve decimated, its no-fit vertices mapped",
          "[pipeline][coarse_to_fine]") {
  GarmentScene scene = sleeve_scene(40, 64, 0.28);
  for (Eigen::Index v = 0; v < scene.garment.vertices.rows(); ++v)
    if (scene.garment.vertices(v, 2) > 0.3) scene.no_fit.push_back(static_cast<int>(v));
  std::string why_not;
  const std::optional<CoarseProxy> proxy = make_coarse_proxy(scene, 600, why_not);
  INFO(why_not);
  REQUIRE(proxy.has_value());
  const TriangleMesh& coarse = proxy->scene.garment;
  CAPTURE(coarse.faces.rows());
  CHECK(coarse.faces.rows() >= 480);
  CHECK(coarse.faces.rows() <= 720);
  CHECK(proxy->fine_vertex.size() == static_cast<std::size_t>(coarse.vertices.rows()));
  CHECK(proxy->clearance > proxy->embedding.max_offset());
  // The rest of the scene is the garment's.
  CHECK(proxy->scene.avatar.faces.rows() == scene.avatar.faces.rows());
  CHECK(proxy->scene.shrunk_avatar == scene.shrunk_avatar);
  // No-fit vertices sit above z = 0.3 on the garment; on the proxy they stay near there.
  REQUIRE_FALSE(proxy->scene.no_fit.empty());
  for (const int v : proxy->scene.no_fit) CHECK(coarse.vertices(v, 2) > 0.2);
  int fitted_high = 0;
  std::vector<bool> listed(static_cast<std::size_t>(coarse.vertices.rows()), false);
  for (const int v : proxy->scene.no_fit) listed[static_cast<std::size_t>(v)] = true;
  for (Eigen::Index v = 0; v < coarse.vertices.rows(); ++v)
    fitted_high += !listed[static_cast<std::size_t>(v)] && coarse.vertices(v, 2) > 0.4;
  CHECK(fitted_high == 0);
}

namespace {

/// The smallest 4√3 area over the sum of squared edges among the faces of `mesh`.
double smallest_face_shape(const TriangleMesh& mesh) {
  double smallest = 1.0;
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    const Vector3d a = mesh.vertices.row(mesh.faces(f, 0)).transpose();
    const Vector3d b = mesh.vertices.row(mesh.faces(f, 1)).transpose();
    const Vector3d c = mesh.vertices.row(mesh.faces(f, 2)).transpose();
    const double squared_edges =
        (b - a).squaredNorm() + (c - a).squaredNorm() + (c - b).squaredNorm();
    smallest =
        std::min(smallest, 2.0 * std::sqrt(3.0) * (b - a).cross(c - a).norm() / squared_edges);
  }
  return smallest;
}

}  // namespace

TEST_CASE("coarse proxy: a subdivided sleeve decimated short of its own faces has no slivers",
          "[pipeline][coarse_to_fine]") {
  // Decimating to twice the sleeve's own faces collapses edges inside its flat faces, where
  // every collapse costs nothing; unchecked, those collapses leave slivers.
  GarmentScene scene = sleeve_scene(12, 32, 0.28);
  const double own_shape = smallest_face_shape(scene.garment);
  const Eigen::Index own_faces = scene.garment.faces.rows();
  scene.garment = subdivide_at_midpoints(subdivide_at_midpoints(scene.garment).mesh).mesh;
  std::string why_not;
  const std::optional<CoarseProxy> proxy =
      make_coarse_proxy(scene, static_cast<int>(2 * own_faces), why_not);
  INFO(why_not);
  REQUIRE(proxy.has_value());
  CAPTURE(own_shape, proxy->scene.garment.faces.rows());
  CHECK(proxy->scene.garment.faces.rows() < 3 * own_faces);
  CHECK(smallest_face_shape(proxy->scene.garment) >= std::min(0.2, own_shape) - 1e-9);
}

TEST_CASE(
    "coarse proxy: none where the proxy would cross the shrunk avatar or the garment "
    "carries ties or crossings",
    "[pipeline][coarse_to_fine]") {
  std::string why_not;
  SECTION("the decimated sleeve's chords cut into a shrunk avatar just inside the sleeve") {
    // 64 segments keep the sleeve's chords at radius 0.5 cos(pi / 64) = 0.4994, outside the
    // shrunk avatar at 0.499; a proxy of a few hundred faces has far fewer segments.
    const GarmentScene scene = sleeve_scene(10, 64, 0.499);
    CHECK_FALSE(make_coarse_proxy(scene, 100, why_not).has_value());
    CHECK_THAT(why_not, Catch::Contains("crosses"));
  }
  SECTION("split edges held by ties") {
    GarmentScene scene = sleeve_scene(10, 64, 0.28);
    scene.ties.push_back({0, 1});
    CHECK_FALSE(make_coarse_proxy(scene, 100, why_not).has_value());
    CHECK_THAT(why_not, Catch::Contains("split edges"));
  }
  SECTION("crossings as given, in tangles") {
    // Layers of an outfit that cross as given: the garment cannot follow a proxy through
    // the crossings, where the two have different pairs left out of contact.
    GarmentScene scene = sleeve_scene(10, 64, 0.28);
    scene.garment_tangles.assign(static_cast<std::size_t>(scene.garment.vertices.rows()), -1);
    scene.garment_tangles[0] = 0;
    CHECK_FALSE(make_coarse_proxy(scene, 100, why_not).has_value());
    CHECK_THAT(why_not, Catch::Contains("crossings"));
  }
}

namespace {

/// `first` and `second` as one mesh, `second`'s vertices after `first`'s.
TriangleMesh joined(const TriangleMesh& first, const TriangleMesh& second) {
  TriangleMesh mesh;
  mesh.vertices.resize(first.vertices.rows() + second.vertices.rows(), 3);
  mesh.vertices << first.vertices, second.vertices;
  mesh.faces.resize(first.faces.rows() + second.faces.rows(), 3);
  mesh.faces << first.faces, second.faces.array() + static_cast<int>(first.vertices.rows());
  return mesh;
}

}  // namespace

TEST_CASE("coarse proxy: layers decimated one by one, each carrying only its own vertices",
          "[pipeline][coarse_to_fine]") {
  // Two short sleeves, fine around and 0.01 apart: their proxies have far fewer segments,
  // each a sleeve of its own.
  GarmentScene scene = sleeve_scene(2, 3, 0.28);
  const TriangleMesh inner = open_cylinder(0.5, -0.2, 0.2, 8, 128);
  scene.garment = joined(inner, open_cylinder(0.51, -0.2, 0.2, 8, 128));
  const auto inner_vertices = static_cast<int>(inner.vertices.rows());
  // The inner sleeve is a skirt, the outer one not.
  std::vector<char> skirt(static_cast<std::size_t>(scene.garment.vertices.rows()), 0);
  std::fill_n(skirt.begin(), inner_vertices, 1);
  scene.skeletons = SkeletonMotion{MatrixX3d(), MatrixX3d(), MatrixX2i(), skirt};
  std::string why_not;
  const std::optional<CoarseProxy> proxy = make_coarse_proxy(scene, 600, why_not);
  INFO(why_not);
  REQUIRE(proxy.has_value());
  const TriangleMesh& coarse = proxy->scene.garment;
  // Each proxy vertex stands for a vertex of its own sleeve, and takes its skirt flag.
  const auto outer_proxy_vertex = [&](int v) {
    return proxy->fine_vertex[static_cast<std::size_t>(v)] >= inner_vertices;
  };
  REQUIRE(proxy->scene.skeletons.has_value());
  const std::vector<char>& proxy_skirt = proxy->scene.skeletons->skirt_vertices;
  REQUIRE(proxy_skirt.size() == static_cast<std::size_t>(coarse.vertices.rows()));
  for (Eigen::Index v = 0; v < coarse.vertices.rows(); ++v) {
    const bool outer = coarse.vertices.row(v).leftCols(2).norm() > 0.505;
    CHECK(outer_proxy_vertex(static_cast<int>(v)) == outer);
    CHECK((proxy_skirt[static_cast<std::size_t>(v)] != 0) == !outer);
  }
  int inner_faces = 0;
  for (Eigen::Index f = 0; f < coarse.faces.rows(); ++f) {
    const bool outer = outer_proxy_vertex(coarse.faces(f, 0));
    CHECK(outer_proxy_vertex(coarse.faces(f, 1)) == outer);
    CHECK(outer_proxy_vertex(coarse.faces(f, 2)) == outer);
    inner_faces += !outer;
  }
  // The same ratio for both: about half the faces each.
  CHECK(std::abs(2 * inner_faces - coarse.faces.rows()) < coarse.faces.rows() / 10);
  // The outer proxy moved, the inner one still: only the outer sleeve's vertices move.
  MatrixX3d moved = coarse.vertices;
  for (Eigen::Index v = 0; v < moved.rows(); ++v)
    if (outer_proxy_vertex(static_cast<int>(v))) moved(v, 0) += 1.0;
  const MatrixX3d carried = proxy->embedding.carry(moved);
  const MatrixX3d motion = carried - scene.garment.vertices;
  CHECK(motion.topRows(inner_vertices).cwiseAbs().maxCoeff() < 1e-9);
  CHECK((motion.bottomRows(motion.rows() - inner_vertices).col(0).array() - 1.0).abs().maxCoeff() <
        1e-9);
}
