#pragma once

#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include "core/common/types.hpp"

namespace gr::exact {

/// The kernel of every exact test in validate/: predicates are exact (filtered, with an
/// exact fallback); constructions such as distances are plain doubles.
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Segment = Kernel::Segment_3;
using Triangle = Kernel::Triangle_3;

/// A face as the simplex it really is: a triangle, a segment (exactly collinear corners)
/// or a point (three identical corners).
struct Simplex {
  enum Kind { kTriangle, kSegment, kPoint } kind;
  Triangle triangle;
  Segment segment;  ///< between the two extreme corners, when kind == kSegment
  Point point;      ///< the first corner
};

/// The simplex spanned by three corners (exactly decided, no tolerance).
Simplex make_simplex(const Point& a, const Point& b, const Point& c);

/// One simplex per face of `mesh` (#F entries, face order).
std::vector<Simplex> make_simplices(const TriangleMesh& mesh);

/// Whether two simplices share at least one point (touching counts), decided exactly.
bool simplices_intersect(const Simplex& x, const Simplex& y);

/// Row `v` of `vertices` (#V×3) as a point.
inline Point point_of(const MatrixX3d& vertices, int v) {
  return Point(vertices(v, 0), vertices(v, 1), vertices(v, 2));
}

}  // namespace gr::exact
