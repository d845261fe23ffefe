#include "validate/measure/surface_distance.hpp"

#include <cmath>
#include <limits>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>
#include <tbb/parallel_for.h>

namespace gr {

namespace {
using Kernel = CGAL::Simple_cartesian<double>;
using Triangle = Kernel::Triangle_3;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, std::vector<Triangle>::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
}  // namespace

std::vector<double> distances_to_surface(const TriangleMesh& surface,
                                         const Eigen::Ref<const MatrixX3d>& points) {
  std::vector<Triangle> triangles;
  triangles.reserve(static_cast<std::size_t>(surface.faces.rows()));
  auto point = [&](int v) {
    return Kernel::Point_3(surface.vertices(v, 0), surface.vertices(v, 1), surface.vertices(v, 2));
  };
  for (Eigen::Index f = 0; f < surface.faces.rows(); ++f) {
    Triangle t(point(surface.faces(f, 0)), point(surface.faces(f, 1)), point(surface.faces(f, 2)));
    if (!t.is_degenerate()) triangles.push_back(t);
  }
  std::vector<double> out(static_cast<std::size_t>(points.rows()),
                          std::numeric_limits<double>::infinity());
  if (triangles.empty()) return out;
  Tree tree(triangles.begin(), triangles.end());
  tree.build();
  tree.accelerate_distance_queries();
  // CGAL builds its search structures lazily: one serial query before the parallel ones.
  if (points.rows() > 0)
    tree.squared_distance(Kernel::Point_3(points(0, 0), points(0, 1), points(0, 2)));
  tbb::parallel_for(Eigen::Index(0), points.rows(), [&](Eigen::Index i) {
    const Kernel::Point_3 p(points(i, 0), points(i, 1), points(i, 2));
    out[static_cast<std::size_t>(i)] = std::sqrt(tree.squared_distance(p));
  });
  return out;
}

}  // namespace gr
