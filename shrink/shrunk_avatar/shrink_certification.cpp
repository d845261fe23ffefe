#include "shrink/shrunk_avatar/shrink_certification.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <tbb/parallel_for.h>

#include "shrink/level_set/triangle_tree.hpp"
#include "validate/checks/mesh_intersections.hpp"

namespace gr {

namespace {

/// Fast winding numbers closer than this to 1/2 are recomputed exactly; the Barnes-Hut
/// error on avatars is about 1e-2.
constexpr double kUncertainWinding = 0.25;

Vector3d corner(const TriangleMesh& mesh, int face, int c) {
  return mesh.vertices.row(mesh.faces(face, c)).transpose();
}

/// Where segment pq meets triangle abc (Möller–Trumbore), if it does.
std::optional<Vector3d> segment_triangle_point(const Vector3d& p, const Vector3d& q,
                                               const Vector3d& a, const Vector3d& b,
                                               const Vector3d& c) {
  const Vector3d direction = q - p, e1 = b - a, e2 = c - a;
  const Vector3d s = direction.cross(e2);
  const double det = e1.dot(s);
  if (std::abs(det) <= std::numeric_limits<double>::min()) return std::nullopt;
  const Vector3d ap = p - a;
  const double u = ap.dot(s) / det;
  const Vector3d r = ap.cross(e1);
  const double v = direction.dot(r) / det;
  const double t = e2.dot(r) / det;
  if (u < 0.0 || v < 0.0 || u + v > 1.0 || t < 0.0 || t > 1.0) return std::nullopt;
  return p + t * direction;
}

/// A point where two intersecting faces meet: an edge of one through the other, else
/// (coplanar or touching cases) the midpoint of their centroids.
Vector3d crossing_point(const TriangleMesh& first, int f, const TriangleMesh& second, int g) {
  for (int pass = 0; pass < 2; ++pass) {
    const TriangleMesh& edges = pass == 0 ? first : second;
    const TriangleMesh& face = pass == 0 ? second : first;
    const int e = pass == 0 ? f : g, t = pass == 0 ? g : f;
    for (int c = 0; c < 3; ++c)
      if (auto hit =
              segment_triangle_point(corner(edges, e, c), corner(edges, e, (c + 1) % 3),
                                     corner(face, t, 0), corner(face, t, 1), corner(face, t, 2)))
        return *hit;
  }
  const Vector3d a = (corner(first, f, 0) + corner(first, f, 1) + corner(first, f, 2)) / 3.0;
  const Vector3d b = (corner(second, g, 0) + corner(second, g, 1) + corner(second, g, 2)) / 3.0;
  return 0.5 * (a + b);
}

}  // namespace

std::optional<ShrinkConflict> find_shrink_conflict(const TriangleMesh& shrunk_avatar,
                                                   const TriangleMesh& garment) {
  const FacePairList crossing = find_intersecting_face_pairs(shrunk_avatar, garment, 1);
  if (crossing.count > 0) {
    ShrinkConflict conflict;
    conflict.kind = ShrinkConflict::Kind::kSurfacesCross;
    conflict.avatar_face = crossing.pairs.front().first;
    conflict.garment_face = crossing.pairs.front().second;
    conflict.position =
        crossing_point(shrunk_avatar, conflict.avatar_face, garment, conflict.garment_face);
    conflict.count = crossing.count;
    return conflict;
  }

  // A garment vertex inside means (surfaces being apart) its whole part is inside.
  const std::vector<int> inside = garment_vertices_inside(shrunk_avatar, garment.vertices);
  if (inside.empty()) return std::nullopt;
  ShrinkConflict conflict;
  conflict.kind = ShrinkConflict::Kind::kGarmentInside;
  conflict.garment_vertex = inside.front();
  conflict.position = garment.vertices.row(conflict.garment_vertex).transpose();
  conflict.count = inside.size();
  return conflict;
}

std::vector<int> garment_vertices_inside(const TriangleMesh& shrunk_avatar,
                                         const Eigen::Ref<const MatrixX3d>& points) {
  // The fast winding number decides only clear cases; near 1/2 the exact sum does, so
  // the Barnes-Hut approximation never decides a certificate.
  const TriangleTree avatar_tree(shrunk_avatar);
  const auto count = static_cast<int>(points.rows());
  std::vector<char> inside(static_cast<std::size_t>(count), 0);
  tbb::parallel_for(0, count, [&](int v) {
    const Vector3d p = points.row(v).transpose();
    double winding = avatar_tree.winding_number(p);
    if (std::abs(std::abs(winding) - 0.5) < kUncertainWinding)
      winding = avatar_tree.exact_winding_number(p);
    inside[static_cast<std::size_t>(v)] = winding_number_inside(winding) ? 1 : 0;
  });
  std::vector<int> listed;
  for (int v = 0; v < count; ++v)
    if (inside[static_cast<std::size_t>(v)]) listed.push_back(v);
  return listed;
}

}  // namespace gr
