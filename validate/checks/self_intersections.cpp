#include "validate/checks/self_intersections.hpp"

#include <array>
#include <atomic>

#include <CGAL/intersections.h>

#include "validate/checks/broad_phase.hpp"
#include "validate/checks/exact_simplex.hpp"
#include "validate/checks/position_identity.hpp"

namespace gr {

namespace {

using exact::Point;
using exact::Segment;
using exact::Simplex;
using exact::Triangle;

/// Corners of two faces reordered so the shared ones come first, in the same order.
struct SharedCorners {
  int count = 0;
  std::array<int, 3> first{};   ///< corner slots (0..2) of the first face
  std::array<int, 3> second{};  ///< corner slots of the second face
};

SharedCorners match_corners(const std::array<int, 3>& a, const std::array<int, 3>& b) {
  SharedCorners s;
  bool used_a[3] = {false, false, false};
  bool used_b[3] = {false, false, false};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (!used_b[j] && a[i] == b[j]) {
        s.first[s.count] = i;
        s.second[s.count] = j;
        used_a[i] = used_b[j] = true;
        ++s.count;
        break;
      }
  int next = s.count;
  for (int i = 0; i < 3; ++i)
    if (!used_a[i]) s.first[next++] = i;
  next = s.count;
  for (int j = 0; j < 3; ++j)
    if (!used_b[j]) s.second[next++] = j;
  return s;
}

/// Two triangles (p0, p1, p2) and (p0, p1, q2) sharing the edge p0p1.
bool edge_neighbours_overlap(const Point& p0, const Point& p1, const Point& p2, const Point& q2) {
  return CGAL::orientation(p0, p1, p2, q2) == CGAL::COPLANAR &&
         CGAL::coplanar_orientation(p0, p1, p2, q2) == CGAL::POSITIVE;
}

/// Two triangles (v, p1, p2) and (v, q1, q2) sharing only the vertex v.
bool vertex_neighbours_overlap(const Triangle& t, const Triangle& u, const Point& p1,
                               const Point& p2, const Point& q1, const Point& q2) {
  return CGAL::do_intersect(Segment(p1, p2), u) || CGAL::do_intersect(Segment(q1, q2), t);
}

}  // namespace

SelfIntersections find_self_intersecting_face_pairs(const TriangleMesh& mesh,
                                                    std::size_t max_listed) {
  return self_intersecting_among(mesh, overlapping_face_boxes(mesh), max_listed);
}

SelfIntersections self_intersecting_among(const TriangleMesh& mesh,
                                          const std::vector<FacePair>& candidates,
                                          std::size_t max_listed) {
  const std::vector<int> identity = position_identity(mesh.vertices);
  const std::vector<Simplex> simplices = exact::make_simplices(mesh);
  auto corners = [&](int f) {
    return std::array<int, 3>{identity[static_cast<std::size_t>(mesh.faces(f, 0))],
                              identity[static_cast<std::size_t>(mesh.faces(f, 1))],
                              identity[static_cast<std::size_t>(mesh.faces(f, 2))]};
  };
  auto corner_point = [&](int f, int slot) {
    return exact::point_of(mesh.vertices, mesh.faces(f, slot));
  };

  std::atomic<std::size_t> untested{0};
  SelfIntersections result;
  result.pairs = keep_intersecting(
      candidates,
      [&](const FacePair& pair) {
        const Simplex& a = simplices[static_cast<std::size_t>(pair.first)];
        const Simplex& b = simplices[static_cast<std::size_t>(pair.second)];
        const SharedCorners shared = match_corners(corners(pair.first), corners(pair.second));
        if (shared.count == 0) return exact::simplices_intersect(a, b);
        if (a.kind != Simplex::kTriangle || b.kind != Simplex::kTriangle) {
          ++untested;
          return false;
        }
        // Non-degenerate faces have three distinct corner positions.
        const auto p = [&](int k) { return corner_point(pair.first, shared.first[k]); };
        const auto q = [&](int k) { return corner_point(pair.second, shared.second[k]); };
        switch (shared.count) {
          case 1: return vertex_neighbours_overlap(a.triangle, b.triangle, p(1), p(2), q(1), q(2));
          case 2: return edge_neighbours_overlap(p(0), p(1), p(2), q(2));
          default: return true;
        }
      },
      max_listed);
  result.untested_degenerate_neighbours = untested.load();
  return result;
}

}  // namespace gr
