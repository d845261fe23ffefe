#include "validate/checks/clearance.hpp"

#include <algorithm>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/narrowphase/distance.h>
#include <tbb/parallel_for.h>

#include "validate/checks/exact_simplex.hpp"
#include "validate/checks/position_identity.hpp"

namespace gr {

namespace {

using Model = fcl::BVHModel<fcl::OBBRSSd>;

std::shared_ptr<Model> make_model(const TriangleMesh& mesh) {
  std::vector<fcl::Vector3d> points(static_cast<std::size_t>(mesh.vertices.rows()));
  for (std::size_t i = 0; i < points.size(); ++i)
    points[i] = mesh.vertices.row(static_cast<Eigen::Index>(i)).transpose();
  std::vector<fcl::Triangle> triangles(static_cast<std::size_t>(mesh.faces.rows()));
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    const auto row = static_cast<Eigen::Index>(f);
    triangles[f] = fcl::Triangle(static_cast<std::size_t>(mesh.faces(row, 0)),
                                 static_cast<std::size_t>(mesh.faces(row, 1)),
                                 static_cast<std::size_t>(mesh.faces(row, 2)));
  }
  auto model = std::make_shared<Model>();
  model->beginModel(static_cast<int>(triangles.size()), static_cast<int>(points.size()));
  model->addSubModel(points, triangles);
  model->endModel();
  return model;
}

using TriangleIterator = std::vector<exact::Triangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<exact::Kernel, TriangleIterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<exact::Kernel, Primitive>>;

}  // namespace

Clearance minimum_clearance(const TriangleMesh& first, const TriangleMesh& second) {
  const std::shared_ptr<Model> a = make_model(first);
  const std::shared_ptr<Model> b = make_model(second);
  fcl::DistanceRequestd request;
  request.enable_nearest_points = true;
  fcl::DistanceResultd result;
  const fcl::Transform3d identity = fcl::Transform3d::Identity();
  fcl::distance(a.get(), identity, b.get(), identity, request, result);
  Clearance c;
  c.distance = std::max(result.min_distance, 0.0);
  c.first_face = static_cast<int>(result.b1);
  c.second_face = static_cast<int>(result.b2);
  c.first_point = result.nearest_points[0];
  c.second_point = result.nearest_points[1];
  return c;
}

std::vector<int> vertices_closer_than(const TriangleMesh& points_mesh, const TriangleMesh& surface,
                                      double threshold) {
  // CGAL's point–triangle distance handles collinear triangles as their longest edge.
  std::vector<exact::Triangle> triangles;
  triangles.reserve(static_cast<std::size_t>(surface.faces.rows()));
  for (Eigen::Index f = 0; f < surface.faces.rows(); ++f)
    triangles.emplace_back(exact::point_of(surface.vertices, surface.faces(f, 0)),
                           exact::point_of(surface.vertices, surface.faces(f, 1)),
                           exact::point_of(surface.vertices, surface.faces(f, 2)));
  Tree tree(triangles.begin(), triangles.end());
  tree.build();
  // Built before the parallel queries: lazy construction is not thread-safe.
  tree.accelerate_distance_queries();

  const std::vector<int> identity = position_identity(points_mesh.vertices);
  std::vector<char> used(identity.size(), 0);
  for (Eigen::Index f = 0; f < points_mesh.faces.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      used[static_cast<std::size_t>(identity[static_cast<std::size_t>(points_mesh.faces(f, c))])] =
          1;
  std::vector<char> near(identity.size(), 0);
  const double threshold_sq = threshold * threshold;
  tbb::parallel_for(std::size_t(0), identity.size(), [&](std::size_t v) {
    if (!used[v]) return;
    const exact::Point p = exact::point_of(points_mesh.vertices, static_cast<int>(v));
    near[v] = tree.squared_distance(p) < threshold_sq ? 1 : 0;
  });
  std::vector<int> out;
  for (std::size_t v = 0; v < near.size(); ++v)
    if (near[v]) out.push_back(static_cast<int>(v));
  return out;
}

}  // namespace gr
