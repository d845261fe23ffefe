#include <algorithm>
#include <array>
#include <random>
#include <set>
#include <tuple>

#include <catch2/catch.hpp>

#include "core/candidates/candidates.hpp"
#include "core/common/errors.hpp"
#include "core/distance/edge_edge_distance.hpp"
#include "core/distance/point_triangle_distance.hpp"
#include "core/io/obj_document.hpp"
#include "core/mesh/simulation_mesh.hpp"
#include "core/mesh/unique_edges.hpp"
#include "test_support.hpp"

using gr::MatrixX3d;
using gr::Vector3d;

namespace {

using Key = std::array<int, 4>;

/// Candidate sets as keys; edge–edge pairs under both orders.
struct CandidateKeys {
  std::set<Key> point_triangle, edge_edge;
  explicit CandidateKeys(const gr::Candidates& c) {
    for (const auto& pt : c.point_triangle)
      point_triangle.insert({pt.point, pt.triangle[0], pt.triangle[1], pt.triangle[2]});
    for (const auto& ee : c.edge_edge) {
      edge_edge.insert({ee.edge_a[0], ee.edge_a[1], ee.edge_b[0], ee.edge_b[1]});
      edge_edge.insert({ee.edge_b[0], ee.edge_b[1], ee.edge_a[0], ee.edge_a[1]});
    }
  }
};

gr::TriangleMesh load(const std::string& file) {
  return gr::make_simulation_mesh(gr::read_obj(gr::test::shared_data(file))).mesh;
}

/// Garment box centre onto the avatar's, then both scaled by 2 / (avatar's largest side).
/// With `match_size` the garment is first brought to the avatar's size: the files' units
/// can differ by far more than the bodies do (the puffer is about 1.5 units wide, the
/// goblin 0.06 units tall), and a garment 30 times the body's size touches nothing.
void place(gr::TriangleMesh& garment, gr::TriangleMesh& avatar, bool match_size) {
  const auto box = [](const MatrixX3d& V) {
    return std::make_pair(V.colwise().minCoeff().eval(), V.colwise().maxCoeff().eval());
  };
  const auto [g_lo, g_hi] = box(garment.vertices);
  const auto [a_lo, a_hi] = box(avatar.vertices);
  const Eigen::RowVector3d a_centre = 0.5 * (a_lo + a_hi);
  const double scale = 2.0 / (a_hi - a_lo).maxCoeff();
  const double garment_scale = match_size ? 2.0 / (g_hi - g_lo).maxCoeff() : scale;
  garment.vertices = ((garment.vertices.rowwise() - 0.5 * (g_lo + g_hi)) * garment_scale).eval();
  avatar.vertices = ((avatar.vertices.rowwise() - a_centre) * scale).eval();
}

MatrixX3d stacked(const gr::TriangleMesh& garment, const gr::TriangleMesh& avatar) {
  MatrixX3d V(garment.vertices.rows() + avatar.vertices.rows(), 3);
  V << garment.vertices, avatar.vertices;
  return V;
}

Vector3d row(const MatrixX3d& V, int i) { return V.row(i).transpose(); }

bool face_has(const gr::MatrixX3i& F, Eigen::Index f, int v) {
  return F(f, 0) == v || F(f, 1) == v || F(f, 2) == v;
}

/// Brute force over every `stride`-th query element: each pair within `radius` must be a
/// candidate. Returns how many pairs were checked.
std::size_t check_against_brute_force(const gr::ContactMesh& mesh, const MatrixX3d& V,
                                      const gr::Candidates& candidates, double radius, int stride) {
  const CandidateKeys keys(candidates);
  const double r_sq = radius * radius;
  std::size_t found = 0;
  const auto point_vs_faces = [&](int v, const gr::MatrixX3i& F) {
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
      if (face_has(F, f, v)) continue;
      if (gr::point_triangle_distance_sq(row(V, v), row(V, F(f, 0)), row(V, F(f, 1)),
                                         row(V, F(f, 2))) >= r_sq)
        continue;
      ++found;
      CAPTURE(v, f);
      REQUIRE(keys.point_triangle.count({v, F(f, 0), F(f, 1), F(f, 2)}) == 1);
    }
  };
  const auto edge_vs_edges = [&](Eigen::Index e, const gr::MatrixX2i& E) {
    const gr::MatrixX2i& G = mesh.garment_edges;
    for (Eigen::Index f = 0; f < E.rows(); ++f) {
      if (G(e, 0) == E(f, 0) || G(e, 0) == E(f, 1) || G(e, 1) == E(f, 0) || G(e, 1) == E(f, 1))
        continue;
      if (gr::edge_edge_distance_sq(row(V, G(e, 0)), row(V, G(e, 1)), row(V, E(f, 0)),
                                    row(V, E(f, 1))) >= r_sq)
        continue;
      ++found;
      CAPTURE(e, f);
      REQUIRE(keys.edge_edge.count({G(e, 0), G(e, 1), E(f, 0), E(f, 1)}) == 1);
    }
  };
  for (int v = 0; v < mesh.garment_vertex_count; v += stride) {
    point_vs_faces(v, mesh.avatar_faces);
    if (mesh.self_contact) point_vs_faces(v, mesh.garment_faces);
  }
  for (int v = mesh.garment_vertex_count; v < mesh.vertex_count(); v += stride)
    point_vs_faces(v, mesh.garment_faces);
  for (Eigen::Index e = 0; e < mesh.garment_edges.rows(); e += stride) {
    edge_vs_edges(e, mesh.avatar_edges);
    if (mesh.self_contact) edge_vs_edges(e, mesh.garment_edges);
  }
  return found;
}

}  // namespace

TEST_CASE("unique edges and the stacked contact mesh", "[candidates]") {
  gr::TriangleMesh garment, avatar;
  garment.vertices.setRandom(4, 3);
  garment.faces.resize(2, 3);
  garment.faces << 0, 1, 2, 2, 1, 3;
  avatar.vertices.setRandom(5, 3);
  avatar.faces.resize(3, 3);
  avatar.faces << 0, 1, 2, 2, 3, 4, 0, 2, 4;

  const gr::MatrixX2i edges = gr::unique_edges(garment.faces);
  REQUIRE(edges.rows() == 5);
  CHECK(edges.row(0) == Eigen::RowVector2i(0, 1));
  CHECK(edges.row(4) == Eigen::RowVector2i(2, 3));
  CHECK((edges.col(0).array() < edges.col(1).array()).all());

  const gr::ContactMesh all = gr::ContactMesh::build(garment, avatar, true);
  CHECK(all.vertex_count() == 9);
  CHECK(all.avatar_faces.minCoeff() == 4);
  CHECK(all.avatar_edges.rows() == 7);
  const gr::ContactMesh some = gr::ContactMesh::build(garment, avatar, false, {1});
  REQUIRE(some.avatar_faces.rows() == 1);
  CHECK(some.avatar_faces.row(0) == Eigen::RowVector3i(6, 7, 8));
  CHECK(some.avatar_edges.rows() == 3);
  CHECK_FALSE(some.self_contact);
  CHECK_THROWS_AS(gr::ContactMesh::build(garment, avatar, true, {3}), gr::InputError);
  garment.faces(0, 0) = 4;
  CHECK_THROWS_AS(gr::ContactMesh::build(garment, avatar, true), gr::InputError);
}

TEST_CASE("candidates: self pairs share no vertex, avatar pairs never appear", "[candidates]") {
  // A garment strip folded onto itself above a flat avatar strip, all within the radius.
  gr::TriangleMesh garment, avatar;
  garment.vertices.resize(6, 3);
  garment.vertices << 0, 0, 0.01, 1, 0, 0.01, 0, 1, 0.01, 1, 1, 0.01, 0, 0, 0.02, 1, 0, 0.02;
  garment.faces.resize(3, 3);
  garment.faces << 0, 1, 2, 2, 1, 3, 4, 5, 2;
  avatar.vertices.resize(4, 3);
  avatar.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0;
  avatar.faces.resize(2, 3);
  avatar.faces << 0, 1, 2, 2, 1, 3;
  for (const bool self : {true, false}) {
    const gr::ContactMesh mesh = gr::ContactMesh::build(garment, avatar, self);
    const MatrixX3d V = stacked(garment, avatar);
    const gr::Candidates c = gr::find_candidates(mesh, V, 0.05);
    bool any_self = false;
    for (const auto& pt : c.point_triangle) {
      const bool point_on_garment = pt.point < 6, triangle_on_garment = pt.triangle[0] < 6;
      CHECK((point_on_garment || triangle_on_garment));  // never avatar against avatar
      CHECK(std::find(pt.triangle.begin(), pt.triangle.end(), pt.point) == pt.triangle.end());
      any_self |= point_on_garment && triangle_on_garment;
    }
    for (const auto& ee : c.edge_edge) {
      CHECK(ee.edge_a[0] < 6);
      for (const int a : ee.edge_a)
        for (const int b : ee.edge_b) CHECK(a != b);
      any_self |= ee.edge_b[0] < 6;
    }
    CHECK(any_self == self);
    check_against_brute_force(mesh, V, c, 0.05, 1);
    CHECK_THROWS_AS(gr::find_candidates(mesh, V.topRows(5), 0.05), std::invalid_argument);
  }
}

TEST_CASE("candidates: faces left out of avatar contact take part only in self pairs",
          "[candidates]") {
  // Two garment quads side by side above a flat avatar; the right quad (faces 2, 3) is left
  // out of the avatar contact, as a pierced cap would be.
  gr::TriangleMesh garment, avatar;
  garment.vertices.resize(6, 3);
  garment.vertices << 0, 0, 0.01, 1, 0, 0.01, 2, 0, 0.01, 0, 1, 0.01, 1, 1, 0.01, 2, 1, 0.01;
  garment.faces.resize(4, 3);
  garment.faces << 0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4;
  avatar.vertices.resize(4, 3);
  avatar.vertices << -1, -1, 0, 3, -1, 0, -1, 2, 0, 3, 2, 0;
  avatar.faces.resize(2, 3);
  avatar.faces << 0, 1, 2, 2, 1, 3;
  gr::ContactMesh mesh = gr::ContactMesh::build(garment, avatar, true);
  mesh.leave_out_of_avatar_contact({2, 3});
  // Vertices 2 and 5 lie only on left-out faces; the shared edge 1-4 stays in.
  CHECK(mesh.garment_point_meets_avatar == std::vector<char>{1, 1, 0, 1, 1, 0});
  const gr::Candidates c = gr::find_candidates(mesh, stacked(garment, avatar), 0.05);
  bool avatar_pair = false;
  for (const auto& pt : c.point_triangle) {
    if (pt.point < 6 && pt.triangle[0] >= 6) {
      avatar_pair = true;
      CHECK(pt.point != 2);
      CHECK(pt.point != 5);
    }
    if (pt.point >= 6) {  // an avatar vertex: never against the left-out faces
      const std::set<int> t(pt.triangle.begin(), pt.triangle.end());
      CHECK(t != std::set<int>{1, 2, 5});
      CHECK(t != std::set<int>{1, 5, 4});
    }
  }
  CHECK(avatar_pair);
  for (const auto& ee : c.edge_edge)
    if (ee.edge_b[0] >= 6) {
      const std::set<int> e(ee.edge_a.begin(), ee.edge_a.end());
      CHECK(e != std::set<int>{2, 5});
      CHECK(e != std::set<int>{1, 2});
    }
  CHECK_THROWS_AS(mesh.leave_out_of_avatar_contact({4}), gr::InputError);
}

TEST_CASE("candidates: tangled self pairs that touch at the start are the only ones left out",
          "[candidates]") {
  // A quad crossing a flap (faces 0-1 and 2), all in one tangle: the flap's edge 4-5 passes
  // through the quad; vertex 6 lies exactly on the quad, vertex 7 just above it.
  gr::TriangleMesh garment, avatar;
  garment.vertices.resize(8, 3);
  garment.vertices << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0.5, 0.5, -0.2, 0.5, 0.5, 0.2, 0.3, 0.2,
      0, 0.3, 0.7, 1e-3;
  garment.faces.resize(4, 3);
  garment.faces << 0, 1, 2, 0, 2, 3, 4, 5, 6, 5, 7, 6;
  avatar.vertices.resize(3, 3);
  avatar.vertices << 5, 5, 5, 6, 5, 5, 5, 6, 5;
  avatar.faces.resize(1, 3);
  avatar.faces << 0, 1, 2;
  gr::ContactMesh mesh = gr::ContactMesh::build(garment, avatar, true);
  CHECK(gr::tangled_pairs_closer_than(mesh, garment.vertices, 1e-6).empty());  // no tangle
  mesh.garment_tangles.assign(8, 0);
  const auto keys = gr::tangled_pairs_closer_than(mesh, garment.vertices, 1e-6);
  CHECK(std::is_sorted(keys.begin(), keys.end()));
  // Vertex 6 on face 0 (0, 1, 2) touches it; vertex 7, 1e-3 above face 1, does not count.
  CHECK(std::binary_search(keys.begin(), keys.end(), std::array<int, 5>{0, 6, 0, 1, 2}));
  for (const auto& key : keys) CHECK(!(key[0] == 0 && key[1] == 7));
  // Every key listed is a pair closer than the gap.
  for (const auto& key : keys) {
    const auto at = [&](int v) -> Vector3d { return garment.vertices.row(v).transpose(); };
    const double d =
        key[0] == 0 ? gr::point_triangle_distance_sq(at(key[1]), at(key[2]), at(key[3]), at(key[4]))
                    : gr::edge_edge_distance_sq(at(key[1]), at(key[2]), at(key[3]), at(key[4]));
    CHECK(d < 1e-12);
  }
  // Left out of the search; the pair at 1e-3 is still found.
  mesh.unmodelled_self_pairs = keys;
  const gr::Candidates c = gr::find_candidates(mesh, stacked(garment, avatar), 0.01);
  bool near_pair = false;
  for (const auto& pt : c.point_triangle) {
    CHECK_FALSE(std::binary_search(keys.begin(), keys.end(), gr::self_pair_key(pt)));
    near_pair |= gr::self_pair_key(pt) == std::array<int, 5>{0, 7, 0, 2, 3};
  }
  CHECK(near_pair);
  for (const auto& ee : c.edge_edge)
    CHECK_FALSE(std::binary_search(keys.begin(), keys.end(), gr::self_pair_key(ee)));
}

TEST_CASE("candidates: beside a crossing, a pair apart at the start stays modelled",
          "[candidates][inherited]") {
  // A sheet of two squares (faces 0-1 the first, split on its diagonal 0-2; faces 2-3 the
  // second). Flap T (6, 7, 10) crosses the first square, its edge 6-7 through the diagonal;
  // face U (7, 8, 9) shares vertex 7 with it and hangs 1e-7 over the second square (face 3):
  // close, in the crossing's neighbourhood, but apart.
  gr::TriangleMesh garment, avatar;
  garment.vertices.resize(11, 3);
  garment.vertices << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 2, 0, 0, 2, 1, 0, 0.5, 0.5, -0.2, 0.5,
      0.5, 0.2, 1.3, 0.6, 1e-7, 1.2, 0.8, 1e-7, 0.4, 0.6, 0.05;
  garment.faces.resize(6, 3);
  garment.faces << 0, 1, 2, 0, 2, 3, 1, 4, 5, 1, 5, 2, 6, 7, 10, 7, 8, 9;
  avatar.vertices.resize(3, 3);
  avatar.vertices << 5, 5, 5, 6, 5, 5, 5, 6, 5;
  avatar.faces.resize(1, 3);
  avatar.faces << 0, 1, 2;
  gr::ContactMesh mesh = gr::ContactMesh::build(garment, avatar, true);
  const std::array<int, 5> through_diagonal{1, 0, 2, 6, 7};
  const std::array<int, 5> hanging_over{0, 8, 1, 2, 5};
  // By neighbourhood (one tangle), the pair hanging over the second square was left out:
  // nothing would have kept U from passing through it.
  mesh.garment_tangles.assign(11, 0);
  const auto by_tangle = gr::tangled_pairs_closer_than(mesh, garment.vertices, 1e-6);
  CHECK(std::binary_search(by_tangle.begin(), by_tangle.end(), hanging_over));
  // By pair: only what touches across the crossing faces (T with faces 0 and 1) is left out.
  mesh.garment_crossing_faces = {{0, 4}, {1, 4}};
  const auto keys = gr::crossing_pairs_closer_than(mesh, garment.vertices, 1e-6);
  CHECK(std::is_sorted(keys.begin(), keys.end()));
  CHECK(std::binary_search(keys.begin(), keys.end(), through_diagonal));
  CHECK_FALSE(std::binary_search(keys.begin(), keys.end(), hanging_over));
  for (const auto& key : keys)
    for (int k = 1; k < 5; ++k) CHECK(key[static_cast<std::size_t>(k)] != 8);
  // Barrier and CCD search it: a crossing of U with the second square cannot form.
  mesh.unmodelled_self_pairs = keys;
  bool searched = false;
  for (const auto& pt : gr::find_candidates(mesh, stacked(garment, avatar), 0.01).point_triangle)
    searched |= gr::self_pair_key(pt) == hanging_over;
  CHECK(searched);
  bool swept = false;
  MatrixX3d moved = stacked(garment, avatar);
  moved(8, 2) = -0.1;  // vertex 8 driven through face 3
  for (const auto& pt :
       gr::find_swept_candidates(mesh, stacked(garment, avatar), moved, 0.0).point_triangle)
    swept |= gr::self_pair_key(pt) == hanging_over;
  CHECK(swept);
  // Without crossing faces nothing is left out.
  mesh.garment_crossing_faces.clear();
  CHECK(gr::crossing_pairs_closer_than(mesh, garment.vertices, 1e-6).empty());
}

namespace {

/// A shared scene placed for contact, stacked.
struct SharedScene {
  gr::ContactMesh mesh;
  MatrixX3d V;
};

SharedScene shared_scene(const std::string& garment_file, const std::string& avatar_file,
                         bool match_size) {
  gr::TriangleMesh garment = load(garment_file), avatar = load(avatar_file);
  place(garment, avatar, match_size);
  return {gr::ContactMesh::build(garment, avatar, true), stacked(garment, avatar)};
}

SharedScene generated_scene() {
  const auto [garment_file, avatar_file, match_size] =
      GENERATE(std::make_tuple(std::string("garments/skirt/garment.obj"),
                               std::string("avatars/foxgirl/avatar.obj"), false),
               std::make_tuple(std::string("garments/puffer/garment.obj"),
                               std::string("avatars/goblin/avatar.obj"), true));
  CAPTURE(garment_file, avatar_file);
  return shared_scene(garment_file, avatar_file, match_size);
}

}  // namespace

TEST_CASE("broad phase finds every pair brute force finds on the shared scenes",
          "[candidates][shared]") {
  const SharedScene scene = generated_scene();
  const double radius = GENERATE(0.002, 0.02);
  CAPTURE(radius);
  const gr::Candidates candidates = gr::find_candidates(scene.mesh, scene.V, radius);
  const std::size_t checked =
      check_against_brute_force(scene.mesh, scene.V, candidates, radius, 17);
  CHECK(checked > 0);
  if (radius > 0.01) CHECK(checked > 1000);
}

TEST_CASE("swept broad phase finds every pair close along the motion", "[candidates][shared]") {
  // The garment moves sideways and the avatar shrinks: pairs that come close at the end
  // or midway must be candidates of the swept query.
  const SharedScene scene = generated_scene();
  const double radius = 0.005;
  MatrixX3d V1 = scene.V;
  V1.topRows(scene.mesh.garment_vertex_count).col(1).array() += 0.01;
  V1.bottomRows(scene.mesh.avatar_vertex_count) *= 0.99;
  const gr::Candidates swept = gr::find_swept_candidates(scene.mesh, scene.V, V1, radius);
  CHECK(check_against_brute_force(scene.mesh, V1, swept, radius, 17) > 0);
  CHECK(check_against_brute_force(scene.mesh, (0.5 * (scene.V + V1)).eval(), swept, radius, 17) >
        0);
  CHECK(swept.size() >= gr::find_candidates(scene.mesh, scene.V, radius).size());
}

TEST_CASE("candidate finder: static queries on a swept motion reuse its pairs",
          "[candidates][shared]") {
  // A point on the last swept motion filters the swept list; one off it searches again.
  // Either way every pair within the radius must be found.
  const SharedScene scene = generated_scene();
  const double radius = 0.005;
  MatrixX3d V1 = scene.V;
  V1.topRows(scene.mesh.garment_vertex_count).col(1).array() += 0.01;
  gr::CandidateFinder finder(scene.mesh);
  const gr::Candidates swept = finder.find_swept(scene.V, V1, radius);
  const MatrixX3d on_motion = 0.3 * scene.V + 0.7 * V1;
  const gr::Candidates filtered = finder.find(on_motion, radius);
  CHECK(filtered.size() <= swept.size());
  CHECK(filtered.size() < gr::find_swept_candidates(scene.mesh, scene.V, V1, radius).size());
  CHECK(check_against_brute_force(scene.mesh, on_motion, filtered, radius, 17) > 0);

  MatrixX3d off_motion = V1;
  off_motion.topRows(scene.mesh.garment_vertex_count).col(1).array() += 0.01;
  const gr::Candidates searched = finder.find(off_motion, radius);
  CHECK(check_against_brute_force(scene.mesh, off_motion, searched, radius, 17) > 0);
  CHECK(searched.size() == gr::find_candidates(scene.mesh, off_motion, radius).size());
}

TEST_CASE("self pairs left out lie inside regions proven fold free along the motion",
          "[candidates][shared]") {
  // The puffer's vertices each moved by up to a few millimetres at random: the separation
  // bound over such a motion is loose, while most of the jacket still cannot fold.
  const SharedScene scene =
      shared_scene("garments/puffer/garment.obj", "avatars/goblin/avatar.obj", true);
  const double radius = 0.005;
  MatrixX3d V1 = scene.V;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> jitter(-0.004, 0.004);
  for (int v = 0; v < scene.mesh.garment_vertex_count; ++v)
    V1.row(v) += Eigen::RowVector3d(jitter(rng), jitter(rng), jitter(rng));

  gr::CandidateFinder finder(scene.mesh);
  REQUIRE(scene.mesh.cull_fold_free);
  const gr::Candidates culled = finder.find_swept(scene.V, V1, radius);
  gr::ContactMesh everywhere_mesh = scene.mesh;
  everywhere_mesh.cull_fold_free = false;
  const gr::Candidates all = gr::find_swept_candidates(everywhere_mesh, scene.V, V1, radius);

  using Key = std::array<int, 4>;
  const auto pt_key = [](const gr::PointTriangleCandidate& c) {
    Key key{c.point, c.triangle[0], c.triangle[1], c.triangle[2]};
    std::sort(key.begin() + 1, key.end());
    return key;
  };
  const auto ee_key = [](const gr::EdgeEdgeCandidate& c) {
    std::array<int, 2> a{std::min(c.edge_a[0], c.edge_a[1]), std::max(c.edge_a[0], c.edge_a[1])};
    std::array<int, 2> b{std::min(c.edge_b[0], c.edge_b[1]), std::max(c.edge_b[0], c.edge_b[1])};
    if (b < a) std::swap(a, b);
    return Key{a[0], a[1], b[0], b[1]};
  };
  std::set<Key> kept_pt, kept_ee;
  for (const auto& c : culled.point_triangle) kept_pt.insert(pt_key(c));
  for (const auto& c : culled.edge_edge) kept_ee.insert(ee_key(c));
  std::set<Key> all_pt, all_ee;
  for (const auto& c : all.point_triangle) all_pt.insert(pt_key(c));
  for (const auto& c : all.edge_edge) all_ee.insert(ee_key(c));
  for (const Key& key : kept_pt) CHECK(all_pt.count(key) == 1);
  for (const Key& key : kept_ee) CHECK(all_ee.count(key) == 1);

  // Each pair left out: all four vertices in one region found fold free.
  const gr::GarmentRegions* regions = finder.regions();
  REQUIRE(regions != nullptr);
  std::vector<std::set<int>> fold_free_vertices;
  for (std::size_t r = 0; r < regions->regions.size(); ++r)
    if (finder.fold_free()[r])
      fold_free_vertices.emplace_back(regions->regions[r].vertices.begin(),
                                      regions->regions[r].vertices.end());
  // Pairs across the seam of two neighbouring leaves are left out when their union is.
  const double threshold = radius + 2e-10;  // the swept query's (CandidateFinder::find_swept)
  for (const auto& entry : regions->leaf_unions)
    if (gr::stays_fold_free(entry.second, scene.mesh.garment_faces, scene.V, V1, threshold))
      fold_free_vertices.emplace_back(entry.second.vertices.begin(), entry.second.vertices.end());
  const auto inside_one = [&](const Key& key) {
    return std::any_of(
        fold_free_vertices.begin(), fold_free_vertices.end(), [&](const std::set<int>& region) {
          return std::all_of(key.begin(), key.end(), [&](int v) { return region.count(v) == 1; });
        });
  };
  std::size_t left_out = 0;
  for (const Key& key : all_pt)
    if (!kept_pt.count(key)) {
      ++left_out;
      CHECK(inside_one(key));
    }
  for (const Key& key : all_ee)
    if (!kept_ee.count(key)) {
      ++left_out;
      CHECK(inside_one(key));
    }
  CHECK(left_out > 0);
  CHECK(finder.mean_fold_free_fraction() > 0.5);
}
