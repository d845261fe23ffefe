#include "validate/checks/exact_simplex.hpp"

#include <algorithm>

#include <CGAL/intersections.h>

namespace gr::exact {

Simplex make_simplex(const Point& a, const Point& b, const Point& c) {
  Simplex s{Simplex::kTriangle, Triangle(a, b, c), Segment(), a};
  if (!CGAL::collinear(a, b, c)) return s;
  if (a == b && b == c) {
    s.kind = Simplex::kPoint;
    return s;
  }
  // Collinear: the segment between the two extreme corners (lexicographic order is the
  // order along the common line).
  const auto smaller = [](const Point& p, const Point& q) {
    return CGAL::lexicographically_xyz_smaller(p, q);
  };
  s.kind = Simplex::kSegment;
  s.segment = Segment(std::min({a, b, c}, smaller), std::max({a, b, c}, smaller));
  return s;
}

std::vector<Simplex> make_simplices(const TriangleMesh& mesh) {
  std::vector<Simplex> out;
  out.reserve(static_cast<std::size_t>(mesh.faces.rows()));
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    out.push_back(make_simplex(point_of(mesh.vertices, mesh.faces(f, 0)),
                               point_of(mesh.vertices, mesh.faces(f, 1)),
                               point_of(mesh.vertices, mesh.faces(f, 2))));
  return out;
}

bool simplices_intersect(const Simplex& x, const Simplex& y) {
  if (x.kind > y.kind) return simplices_intersect(y, x);
  switch (x.kind) {
    case Simplex::kTriangle:
      if (y.kind == Simplex::kTriangle) return CGAL::do_intersect(x.triangle, y.triangle);
      if (y.kind == Simplex::kSegment) return CGAL::do_intersect(x.triangle, y.segment);
      return x.triangle.has_on(y.point);
    case Simplex::kSegment:
      if (y.kind == Simplex::kSegment) return CGAL::do_intersect(x.segment, y.segment);
      return x.segment.has_on(y.point);
    case Simplex::kPoint: return x.point == y.point;
  }
  return false;
}

}  // namespace gr::exact
