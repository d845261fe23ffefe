// The validator against an independent brute force with exact constructions (CGAL's
// Exact_predicates_exact_constructions_kernel): every pair, the intersection itself
// computed, and "beyond the shared part" decided from it.
#include <random>
#include <set>

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/intersections.h>
#include <catch2/catch.hpp>

#include "validate/checks/mesh_intersections.hpp"
#include "validate/checks/self_intersections.hpp"

namespace {

using Epeck = CGAL::Exact_predicates_exact_constructions_kernel;
using P = Epeck::Point_3;
using T = Epeck::Triangle_3;
using S = Epeck::Segment_3;

/// Random triangles on a coarse lattice (multiples of 1/4 in [0, 1]), so touching,
/// coplanar and shared-corner configurations are frequent. Degenerate faces are avoided
/// here: they have their own tests.
gr::TriangleMesh random_soup(std::mt19937& rng, int faces, int pool) {
  std::uniform_int_distribution<int> coordinate(0, 4);
  gr::TriangleMesh m;
  m.vertices.resize(pool, 3);
  for (int v = 0; v < pool; ++v)
    for (int k = 0; k < 3; ++k) m.vertices(v, k) = 0.25 * coordinate(rng);
  std::uniform_int_distribution<int> corner(0, pool - 1);
  std::vector<Eigen::RowVector3i> rows;
  while (static_cast<int>(rows.size()) < faces) {
    const Eigen::RowVector3i f(corner(rng), corner(rng), corner(rng));
    auto p = [&](int c) {
      return P(m.vertices(f[c], 0), m.vertices(f[c], 1), m.vertices(f[c], 2));
    };
    if (!CGAL::collinear(p(0), p(1), p(2))) rows.push_back(f);
  }
  m.faces.resize(faces, 3);
  for (int i = 0; i < faces; ++i) m.faces.row(i) = rows[static_cast<std::size_t>(i)];
  return m;
}

T exact_triangle(const gr::TriangleMesh& m, int f) {
  auto p = [&](int c) {
    const int v = m.faces(f, c);
    return P(m.vertices(v, 0), m.vertices(v, 1), m.vertices(v, 2));
  };
  return T(p(0), p(1), p(2));
}

/// Whether two triangles meet outside the convex hull of their common corners.
bool meet_beyond_shared(const T& a, const T& b) {
  std::vector<P> shared;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (a.vertex(i) == b.vertex(j)) shared.push_back(a.vertex(i));
  if (shared.size() == 3) return true;  // a duplicated face lies on itself
  const auto meet = CGAL::intersection(a, b);
  if (!meet) return false;
  auto inside_shared = [&](const P& q) {
    if (shared.size() == 1) return q == shared[0];
    return shared.size() == 2 && S(shared[0], shared[1]).has_on(q);
  };
  if (const P* q = boost::get<P>(&*meet)) return !inside_shared(*q);
  if (const S* s = boost::get<S>(&*meet))
    return !(inside_shared(s->source()) && inside_shared(s->target()));
  if (const T* t = boost::get<T>(&*meet))
    return !(inside_shared(t->vertex(0)) && inside_shared(t->vertex(1)) &&
             inside_shared(t->vertex(2)));
  // A coplanar overlap with four or more corners has area: never inside an edge or point.
  return true;
}

std::set<std::pair<int, int>> as_set(const gr::FacePairList& list) {
  std::set<std::pair<int, int>> out;
  for (const gr::FacePair& p : list.pairs) out.insert({p.first, p.second});
  return out;
}

}  // namespace

TEST_CASE("garment-avatar pairs agree with an exact brute force", "[validate][cross-check]") {
  const unsigned seed = GENERATE(1u, 2u, 3u, 4u, 5u);
  CAPTURE(seed);
  std::mt19937 rng(seed);
  const gr::TriangleMesh a = random_soup(rng, 40, 30);
  const gr::TriangleMesh b = random_soup(rng, 40, 30);
  std::set<std::pair<int, int>> expected;
  for (int i = 0; i < a.faces.rows(); ++i)
    for (int j = 0; j < b.faces.rows(); ++j)
      if (CGAL::do_intersect(exact_triangle(a, i), exact_triangle(b, j))) expected.insert({i, j});
  const gr::FacePairList found = gr::find_intersecting_face_pairs(a, b);
  CHECK(found.count == expected.size());
  CHECK(as_set(found) == expected);
  CHECK_FALSE(expected.empty());  // the lattice makes the test meaningful
}

TEST_CASE("self-intersections agree with an exact brute force", "[validate][cross-check]") {
  const unsigned seed = GENERATE(11u, 12u, 13u, 14u, 15u, 16u);
  CAPTURE(seed);
  std::mt19937 rng(seed);
  // A small vertex pool: many faces share one corner or an edge.
  const gr::TriangleMesh m = random_soup(rng, 40, 12);
  std::set<std::pair<int, int>> expected;
  std::size_t sharing = 0;
  for (int i = 0; i < m.faces.rows(); ++i)
    for (int j = i + 1; j < m.faces.rows(); ++j) {
      const T a = exact_triangle(m, i), b = exact_triangle(m, j);
      for (int c = 0; c < 3; ++c)
        if (b.vertex(c) == a.vertex(0) || b.vertex(c) == a.vertex(1) ||
            b.vertex(c) == a.vertex(2)) {
          ++sharing;
          break;
        }
      if (meet_beyond_shared(a, b)) expected.insert({i, j});
    }
  const gr::SelfIntersections found = gr::find_self_intersecting_face_pairs(m);
  CHECK(found.untested_degenerate_neighbours == 0);
  CHECK(found.pairs.count == expected.size());
  CHECK(as_set(found.pairs) == expected);
  CHECK(sharing > 0);
  CHECK(expected.size() < static_cast<std::size_t>(m.faces.rows() * (m.faces.rows() - 1) / 2));
}
