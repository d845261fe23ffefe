#include "tools/pipeline/coarse_proxy.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Bounded_normal_change_filter.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Count_ratio_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>
#include <fmt/format.h>

#include "validate/checks/degenerate_faces.hpp"
#include "validate/checks/mesh_intersections.hpp"
#include "validate/checks/self_intersections.hpp"

namespace gr {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;
using TriangleIterator = std::vector<Triangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, TriangleIterator>;
using AabbTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
using SurfaceMesh = CGAL::Surface_mesh<Point>;
namespace PMP = CGAL::Polygon_mesh_processing;
namespace SMS = CGAL::Surface_mesh_simplification;

Point point_of(const MatrixX3d& vertices, int v) {
  return {vertices(v, 0), vertices(v, 1), vertices(v, 2)};
}

Vector3d vector_of(const Point& p) { return {p.x(), p.y(), p.z()}; }

std::vector<Triangle> triangles_of(const TriangleMesh& mesh) {
  std::vector<Triangle> triangles;
  triangles.reserve(static_cast<std::size_t>(mesh.faces.rows()));
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    triangles.emplace_back(point_of(mesh.vertices, mesh.faces(f, 0)),
                           point_of(mesh.vertices, mesh.faces(f, 1)),
                           point_of(mesh.vertices, mesh.faces(f, 2)));
  return triangles;
}

/// A garment edge whose ends lie on two proxy faces cuts inside the proxy where it bends,
/// by about its length times a quarter of the bend angle; this is that depth for bends up
/// to about 40 degrees, in garment edge lengths.
constexpr double kChordDepth = 0.25;

double median_edge_length(const TriangleMesh& mesh) {
  std::vector<double> lengths;
  lengths.reserve(static_cast<std::size_t>(3 * mesh.faces.rows()));
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      lengths.push_back(
          (mesh.vertices.row(mesh.faces(f, k)) - mesh.vertices.row(mesh.faces(f, (k + 1) % 3)))
              .norm());
  if (lengths.empty()) return 0.0;
  const auto middle = lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2);
  std::nth_element(lengths.begin(), middle, lengths.end());
  return *middle;
}

/// A face's frame: its first edge, the normal's cross product with it, and the unit normal;
/// false when the face is degenerate.
bool face_frame(const Vector3d& a, const Vector3d& b, const Vector3d& c,
                std::array<Vector3d, 3>& frame) {
  const Vector3d edge = b - a;
  const Vector3d normal = edge.cross(c - a);
  const double edge_length = edge.norm();
  const double normal_length = normal.norm();
  if (!(edge_length > 0.0) || !(normal_length > 0.0)) return false;
  frame[0] = edge / edge_length;
  frame[2] = normal / normal_length;
  frame[1] = frame[2].cross(frame[0]);
  return true;
}

/// Barycentric coordinates of p (a point of the triangle's plane) in triangle (a, b, c);
/// the first corner's when the triangle is degenerate.
Vector3d barycentric(const Vector3d& p, const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  const Vector3d e0 = b - a, e1 = c - a, d = p - a;
  const double d00 = e0.dot(e0), d01 = e0.dot(e1), d11 = e1.dot(e1);
  const double d20 = d.dot(e0), d21 = d.dot(e1);
  const double denominator = d00 * d11 - d01 * d01;
  if (!(std::abs(denominator) > 0.0)) return Vector3d(1.0, 0.0, 0.0);
  const double v = (d11 * d20 - d01 * d21) / denominator;
  const double w = (d00 * d21 - d01 * d20) / denominator;
  return Vector3d(1.0 - v - w, v, w);
}

Vector3d corner(const Eigen::Ref<const MatrixX3d>& vertices, const MatrixX3i& faces, int f, int k) {
  return vertices.row(faces(f, k)).transpose();
}

/// A proxy face's shape below which a collapse is refused: 4√3 area over the sum of its
/// squared edges, 1 for an equilateral triangle. Decimating a subdivided garment short of
/// its original faces collapses edges inside flat triangles, where every collapse costs
/// nothing, and leaves slivers that a garment carried on them cannot follow.
constexpr double kSmallestProxyShape = 0.2;

/// 4√3 area over the sum of squared edges of triangle (a, b, c).
double triangle_shape(const Point& a, const Point& b, const Point& c) {
  const Kernel::Vector_3 ab = b - a, ac = c - a, bc = c - b;
  const double squared_edges = ab.squared_length() + ac.squared_length() + bc.squared_length();
  if (!(squared_edges > 0.0)) return 0.0;
  const double area = 0.5 * std::sqrt(CGAL::cross_product(ab, ac).squared_length());
  return 4.0 * std::sqrt(3.0) * area / squared_edges;
}

/// An edge-collapse filter (CGAL's filter concept) that refuses a collapse leaving a face of
/// shape below kSmallestProxyShape around the placed vertex.
struct KeepTriangleShapes {
  template <typename Profile>
  boost::optional<typename Profile::Point> operator()(
      const Profile& profile, boost::optional<typename Profile::Point> placement) const {
    if (!placement) return placement;
    const auto& points = profile.vertex_point_map();
    auto triangle = profile.triangles().begin();
    // The first triangles are the ones the collapse removes: those beside the edge.
    if (profile.left_face_exists()) ++triangle;
    if (profile.right_face_exists()) ++triangle;
    for (; triangle != profile.triangles().end(); ++triangle)
      if (triangle_shape(get(points, triangle->v0), *placement, get(points, triangle->v2)) <
          kSmallestProxyShape)
        return boost::none;
    return placement;
  }
};

/// The garment decimated by edge collapses (Lindstrom–Turk; no collapse that turns a face's
/// normal by more than a right angle or leaves a sliver), or empty when CGAL cannot read it
/// as a surface.
std::optional<TriangleMesh> decimate(const TriangleMesh& garment, int target_faces) {
  std::vector<Point> points;
  points.reserve(static_cast<std::size_t>(garment.vertices.rows()));
  for (Eigen::Index v = 0; v < garment.vertices.rows(); ++v)
    points.push_back(point_of(garment.vertices, static_cast<int>(v)));
  std::vector<std::array<std::size_t, 3>> polygons;
  for (Eigen::Index f = 0; f < garment.faces.rows(); ++f)
    polygons.push_back({static_cast<std::size_t>(garment.faces(f, 0)),
                        static_cast<std::size_t>(garment.faces(f, 1)),
                        static_cast<std::size_t>(garment.faces(f, 2))});
  // Orienting splits the vertices where the faces around them do not form one fan, which
  // a halfedge mesh needs.
  PMP::orient_polygon_soup(points, polygons);
  if (!PMP::is_polygon_soup_a_polygon_mesh(polygons)) return std::nullopt;
  SurfaceMesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  const double edge_ratio =
      std::min(1.0, static_cast<double>(target_faces) / static_cast<double>(garment.faces.rows()));
  SMS::Count_ratio_stop_predicate<SurfaceMesh> stop(edge_ratio);
  SMS::edge_collapse(
      mesh, stop,
      CGAL::parameters::filter(SMS::Bounded_normal_change_filter<KeepTriangleShapes>()));
  mesh.collect_garbage();

  TriangleMesh proxy;
  proxy.vertices.resize(static_cast<Eigen::Index>(mesh.number_of_vertices()), 3);
  for (const SurfaceMesh::Vertex_index v : mesh.vertices())
    proxy.vertices.row(static_cast<Eigen::Index>(v.idx())) = vector_of(mesh.point(v)).transpose();
  proxy.faces.resize(static_cast<Eigen::Index>(mesh.number_of_faces()), 3);
  Eigen::Index row = 0;
  for (const SurfaceMesh::Face_index f : mesh.faces()) {
    int k = 0;
    for (const SurfaceMesh::Vertex_index v : CGAL::vertices_around_face(mesh.halfedge(f), mesh))
      proxy.faces(row, k++) = static_cast<int>(v.idx());
    ++row;
  }
  return proxy;
}

/// Per row of `points`, the nearest vertex of `surface` among the corners of the
/// surface face nearest it.
std::vector<int> nearest_vertices(const MatrixX3d& points, const TriangleMesh& surface) {
  const std::vector<Triangle> triangles = triangles_of(surface);
  AabbTree tree(triangles.begin(), triangles.end());
  tree.accelerate_distance_queries();
  std::vector<int> nearest(static_cast<std::size_t>(points.rows()));
  for (Eigen::Index v = 0; v < points.rows(); ++v) {
    const Point p = point_of(points, static_cast<int>(v));
    const auto hit = tree.closest_point_and_primitive(p);
    const int f = static_cast<int>(hit.second - triangles.begin());
    int best = surface.faces(f, 0);
    double best_distance_sq = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
      const int corner_vertex = surface.faces(f, k);
      const double distance_sq =
          (surface.vertices.row(corner_vertex) - points.row(v)).squaredNorm();
      if (distance_sq < best_distance_sq) {
        best_distance_sq = distance_sq;
        best = corner_vertex;
      }
    }
    nearest[static_cast<std::size_t>(v)] = best;
  }
  return nearest;
}

/// The avatar faces the garment's contact models, at the shrunk positions.
TriangleMesh modelled_shrunk_avatar(const GarmentScene& scene) {
  TriangleMesh shrunk{scene.shrunk_avatar, scene.avatar.faces};
  if (scene.avatar_faces_used.empty()) return shrunk;
  shrunk.faces.resize(static_cast<Eigen::Index>(scene.avatar_faces_used.size()), 3);
  for (std::size_t k = 0; k < scene.avatar_faces_used.size(); ++k)
    shrunk.faces.row(static_cast<Eigen::Index>(k)) =
        scene.avatar.faces.row(scene.avatar_faces_used[k]);
  return shrunk;
}

}  // namespace

SurfaceEmbedding::SurfaceEmbedding(const TriangleMesh& coarse, const MatrixX3d& fine_vertices)
    : faces_(coarse.faces) {
  const std::vector<Triangle> triangles = triangles_of(coarse);
  AabbTree tree(triangles.begin(), triangles.end());
  tree.accelerate_distance_queries();
  placements_.resize(static_cast<std::size_t>(fine_vertices.rows()));
  for (Eigen::Index v = 0; v < fine_vertices.rows(); ++v) {
    const Vector3d x = fine_vertices.row(v).transpose();
    const auto hit = tree.closest_point_and_primitive(Point(x.x(), x.y(), x.z()));
    Placement& placement = placements_[static_cast<std::size_t>(v)];
    placement.face = static_cast<int>(hit.second - triangles.begin());
    const int f = placement.face;
    const Vector3d a = corner(coarse.vertices, faces_, f, 0);
    const Vector3d b = corner(coarse.vertices, faces_, f, 1);
    const Vector3d c = corner(coarse.vertices, faces_, f, 2);
    placement.barycentric = barycentric(vector_of(hit.first), a, b, c);
    const Vector3d on_face =
        placement.barycentric[0] * a + placement.barycentric[1] * b + placement.barycentric[2] * c;
    std::array<Vector3d, 3> frame;
    const Vector3d offset = x - on_face;
    max_offset_ = std::max(max_offset_, offset.norm());
    if (face_frame(a, b, c, frame))
      placement.offset = Vector3d(offset.dot(frame[0]), offset.dot(frame[1]), offset.dot(frame[2]));
    else
      placement.offset = offset;  // kept in world axes: the face has no frame of its own
  }
}

MatrixX3d SurfaceEmbedding::carry(const Eigen::Ref<const MatrixX3d>& coarse_vertices) const {
  MatrixX3d fine(static_cast<Eigen::Index>(placements_.size()), 3);
  for (std::size_t v = 0; v < placements_.size(); ++v) {
    const Placement& placement = placements_[v];
    const Vector3d a = corner(coarse_vertices, faces_, placement.face, 0);
    const Vector3d b = corner(coarse_vertices, faces_, placement.face, 1);
    const Vector3d c = corner(coarse_vertices, faces_, placement.face, 2);
    Vector3d x =
        placement.barycentric[0] * a + placement.barycentric[1] * b + placement.barycentric[2] * c;
    std::array<Vector3d, 3> frame;
    if (face_frame(a, b, c, frame))
      x += placement.offset[0] * frame[0] + placement.offset[1] * frame[1] +
           placement.offset[2] * frame[2];
    fine.row(static_cast<Eigen::Index>(v)) = x.transpose();
  }
  return fine;
}

std::optional<CoarseProxy> make_coarse_proxy(const GarmentScene& fine, int target_faces,
                                             std::string& why_not) {
  if (!fine.ties.empty() || !fine.attachments.empty() || !fine.garment_tangles.empty() ||
      !fine.faces_without_avatar_contact.empty()) {
    why_not =
        "the garment has split edges, attached pieces, crossings or faces out of the avatar "
        "contact, which a decimated proxy cannot stand for";
    return std::nullopt;
  }
  std::optional<TriangleMesh> decimated = decimate(fine.garment, target_faces);
  if (!decimated) {
    why_not = "the garment is not a surface CGAL's decimation can read";
    return std::nullopt;
  }
  if (!find_degenerate_faces(*decimated).empty()) {
    why_not = "the decimated garment has degenerate faces";
    return std::nullopt;
  }
  const std::size_t self_crossings = find_self_intersecting_face_pairs(*decimated, 0).pairs.count;
  const std::size_t avatar_crossings =
      find_intersecting_face_pairs(*decimated, modelled_shrunk_avatar(fine), 0).count;
  if (self_crossings > 0 || avatar_crossings > 0) {
    why_not = fmt::format(
        "the decimated garment crosses itself in {} face pairs and the shrunk avatar in {}",
        self_crossings, avatar_crossings);
    return std::nullopt;
  }

  CoarseProxy proxy;
  proxy.fine_vertex = nearest_vertices(decimated->vertices, fine.garment);
  proxy.embedding = SurfaceEmbedding(*decimated, fine.garment.vertices);
  proxy.clearance = proxy.embedding.max_offset() + kChordDepth * median_edge_length(fine.garment);
  proxy.edge_length = median_edge_length(*decimated);
  GarmentScene& scene = proxy.scene;
  scene = fine;
  scene.garment = std::move(*decimated);
  std::vector<bool> no_fit(static_cast<std::size_t>(fine.garment.vertices.rows()), false);
  for (const int v : fine.no_fit) no_fit[static_cast<std::size_t>(v)] = true;
  scene.no_fit.clear();
  scene.fit_offsets.clear();
  for (std::size_t v = 0; v < proxy.fine_vertex.size(); ++v) {
    const auto nearest = static_cast<std::size_t>(proxy.fine_vertex[v]);
    if (no_fit[nearest]) scene.no_fit.push_back(static_cast<int>(v));
    if (!fine.fit_offsets.empty()) scene.fit_offsets.push_back(fine.fit_offsets[nearest]);
  }
  return proxy;
}

}  // namespace gr
