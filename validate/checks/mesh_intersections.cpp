#include "validate/checks/mesh_intersections.hpp"

#include <algorithm>
#include <mutex>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>
#include <tbb/parallel_for.h>

namespace gr {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Segment = Kernel::Segment_3;
using Triangle = Kernel::Triangle_3;
using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, int>;

/// A face as the simplex it really is: triangle, segment (collinear corners) or point.
struct Simplex {
  enum Kind { kTriangle, kSegment, kPoint } kind;
  Triangle triangle;
  Segment segment;
  Point point;
};

Simplex make_simplex(const Point& a, const Point& b, const Point& c) {
  Simplex s{Simplex::kTriangle, Triangle(a, b, c), Segment(), a};
  if (!CGAL::collinear(a, b, c)) return s;
  if (a == b && b == c) {
    s.kind = Simplex::kPoint;
    return s;
  }
  // Collinear: the segment between the two extreme corners (lexicographic order is the
  // order along the common line).
  const Point lo = std::min({a, b, c}, [](const Point& p, const Point& q) {
    return CGAL::lexicographically_xyz_smaller(p, q);
  });
  const Point hi = std::max({a, b, c}, [](const Point& p, const Point& q) {
    return CGAL::lexicographically_xyz_smaller(p, q);
  });
  s.kind = Simplex::kSegment;
  s.segment = Segment(lo, hi);
  return s;
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
    case Simplex::kPoint:
      return x.point == y.point;
  }
  return false;
}

std::vector<Simplex> make_simplices(const TriangleMesh& mesh) {
  std::vector<Simplex> out;
  out.reserve(static_cast<std::size_t>(mesh.faces.rows()));
  auto point = [&](int v) {
    return Point(mesh.vertices(v, 0), mesh.vertices(v, 1), mesh.vertices(v, 2));
  };
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    out.push_back(make_simplex(point(mesh.faces(f, 0)), point(mesh.faces(f, 1)),
                               point(mesh.faces(f, 2))));
  return out;
}

std::vector<Box> make_boxes(const TriangleMesh& mesh) {
  std::vector<Box> boxes;
  boxes.reserve(static_cast<std::size_t>(mesh.faces.rows()));
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    double lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
      lo[k] = hi[k] = mesh.vertices(mesh.faces(f, 0), k);
      for (int c = 1; c < 3; ++c) {
        lo[k] = std::min(lo[k], mesh.vertices(mesh.faces(f, c), k));
        hi[k] = std::max(hi[k], mesh.vertices(mesh.faces(f, c), k));
      }
    }
    boxes.emplace_back(lo, hi, static_cast<int>(f));
  }
  return boxes;
}

}  // namespace

FacePairList find_intersecting_face_pairs(const TriangleMesh& first, const TriangleMesh& second,
                                          std::size_t max_listed) {
  std::vector<Box> first_boxes = make_boxes(first);
  std::vector<Box> second_boxes = make_boxes(second);
  std::vector<FacePair> overlapping;
  // Closed boxes: touching boxes are reported, so touching faces reach the exact test.
  CGAL::box_intersection_d(first_boxes.begin(), first_boxes.end(), second_boxes.begin(),
                           second_boxes.end(), [&](const Box& a, const Box& b) {
                             overlapping.push_back({a.info(), b.info()});
                           });

  const std::vector<Simplex> first_simplices = make_simplices(first);
  const std::vector<Simplex> second_simplices = make_simplices(second);
  std::vector<char> hit(overlapping.size(), 0);
  tbb::parallel_for(std::size_t(0), overlapping.size(), [&](std::size_t i) {
    hit[i] = simplices_intersect(first_simplices[static_cast<std::size_t>(overlapping[i].first)],
                                 second_simplices[static_cast<std::size_t>(overlapping[i].second)]);
  });

  FacePairList result;
  for (std::size_t i = 0; i < overlapping.size(); ++i)
    if (hit[i]) result.pairs.push_back(overlapping[i]);
  std::sort(result.pairs.begin(), result.pairs.end(), [](const FacePair& a, const FacePair& b) {
    return a.first != b.first ? a.first < b.first : a.second < b.second;
  });
  result.count = result.pairs.size();
  if (result.pairs.size() > max_listed) result.pairs.resize(max_listed);
  return result;
}

}  // namespace gr
