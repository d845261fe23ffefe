#include "garment/layers/surface_rays.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

namespace gr {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Triangle = Kernel::Triangle_3;
using TriangleIterator = std::vector<Triangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, TriangleIterator>;
using AabbTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

Kernel::Point_3 to_point(const Vector3d& p) { return {p.x(), p.y(), p.z()}; }
Vector3d to_vector(const Kernel::Point_3& p) { return {p.x(), p.y(), p.z()}; }

Kernel::Ray_3 to_ray(const Vector3d& origin, const Vector3d& direction) {
  return {to_point(origin), Kernel::Vector_3(direction.x(), direction.y(), direction.z())};
}

/// Distance along the ray to where it meets the triangle, given that it does.
double hit_distance(const Triangle& t, const Vector3d& origin, const Vector3d& direction) {
  const Vector3d a = to_vector(t[0]), b = to_vector(t[1]), c = to_vector(t[2]);
  const Vector3d normal = (b - a).cross(c - a);
  const double along = normal.dot(direction);
  // Below this cosine the ray runs in the plane: the plane formula would divide by noise.
  constexpr double kInPlaneCosine = 1e-12;
  if (std::abs(along) > kInPlaneCosine * normal.norm())
    return std::max(0.0, normal.dot(a - origin) / along);
  double nearest = std::max(0.0, (a - origin).dot(direction));
  for (const Vector3d& corner : {b, c})
    nearest = std::min(nearest, std::max(0.0, (corner - origin).dot(direction)));
  return nearest;
}
}  // namespace

struct SurfaceRays::Tree {
  std::vector<Triangle> triangles;
  std::vector<int> face_of;  ///< per triangle, its row in the surface's faces
  AabbTree tree;
};

SurfaceRays::SurfaceRays(const TriangleMesh& surface) : tree_(std::make_unique<Tree>()) {
  const auto corner = [&](Eigen::Index f, int k) {
    return to_point(surface.vertices.row(surface.faces(f, k)).transpose());
  };
  for (Eigen::Index f = 0; f < surface.faces.rows(); ++f) {
    Triangle t(corner(f, 0), corner(f, 1), corner(f, 2));
    if (t.is_degenerate()) continue;
    tree_->triangles.push_back(t);
    tree_->face_of.push_back(static_cast<int>(f));
  }
  tree_->tree.insert(tree_->triangles.cbegin(), tree_->triangles.cend());
  if (!tree_->triangles.empty()) tree_->tree.build();
}

SurfaceRays::~SurfaceRays() = default;
SurfaceRays::SurfaceRays(SurfaceRays&&) noexcept = default;
SurfaceRays& SurfaceRays::operator=(SurfaceRays&&) noexcept = default;

std::vector<RayHit> SurfaceRays::hits(const Vector3d& origin, const Vector3d& direction) const {
  std::vector<TriangleIterator> met;
  if (!empty())
    tree_->tree.all_intersected_primitives(to_ray(origin, direction), std::back_inserter(met));
  std::vector<RayHit> out;
  out.reserve(met.size());
  for (const TriangleIterator& t : met)
    out.push_back({hit_distance(*t, origin, direction),
                   tree_->face_of[static_cast<std::size_t>(t - tree_->triangles.cbegin())]});
  std::sort(out.begin(), out.end(), [](const RayHit& a, const RayHit& b) {
    return a.distance != b.distance ? a.distance < b.distance : a.face < b.face;
  });
  return out;
}

bool SurfaceRays::meets(const Vector3d& origin, const Vector3d& direction) const {
  return !empty() && tree_->tree.do_intersect(to_ray(origin, direction));
}

bool SurfaceRays::empty() const { return tree_->triangles.empty(); }

Vector3d unit_perpendicular(const Vector3d& axis) {
  Eigen::Index least = 0;
  axis.cwiseAbs().minCoeff(&least);
  return axis.cross(Vector3d::Unit(least)).normalized();
}

FaceFrames face_frames(const TriangleMesh& mesh) {
  const Eigen::Index n = mesh.faces.rows();
  FaceFrames out{MatrixX3d(n, 3), MatrixX3d(n, 3)};
  for (Eigen::Index f = 0; f < n; ++f) {
    const Vector3d a = mesh.vertices.row(mesh.faces(f, 0)).transpose();
    const Vector3d b = mesh.vertices.row(mesh.faces(f, 1)).transpose();
    const Vector3d c = mesh.vertices.row(mesh.faces(f, 2)).transpose();
    const Vector3d normal = (b - a).cross(c - a);
    const double area2 = normal.norm();
    out.normals.row(f) =
        area2 > 0.0 ? RowVector3d(normal.transpose() / area2) : RowVector3d::Zero();
    out.centroids.row(f) = ((a + b + c) / 3.0).transpose();
  }
  return out;
}

}  // namespace gr
