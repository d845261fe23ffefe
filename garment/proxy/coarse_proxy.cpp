#include "garment/proxy/coarse_proxy.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <numeric>

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

#include "core/mesh/pieces.hpp"
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

Triangle triangle_of(const TriangleMesh& mesh, Eigen::Index f) {
  return {point_of(mesh.vertices, mesh.faces(f, 0)), point_of(mesh.vertices, mesh.faces(f, 1)),
          point_of(mesh.vertices, mesh.faces(f, 2))};
}

/// The faces of a mesh nearest given points, searched among one piece's faces at a time: a
/// point of one garment must not land on another lying over it (a layer over a layer, a
/// pocket on its base cloth).
class PieceFaceSearch {
 public:
  /// @param face_piece per face of `mesh`, its piece; empty: all one piece.
  /// @pre mesh has at least one face.
  PieceFaceSearch(const TriangleMesh& mesh, const std::vector<int>& face_piece) {
    const auto count = static_cast<std::size_t>(mesh.faces.rows());
    const auto piece_of = [&](std::size_t f) { return face_piece.empty() ? 0 : face_piece[f]; };
    face_of_.resize(count);
    std::iota(face_of_.begin(), face_of_.end(), 0);
    std::stable_sort(face_of_.begin(), face_of_.end(), [&](int a, int b) {
      return piece_of(static_cast<std::size_t>(a)) < piece_of(static_cast<std::size_t>(b));
    });
    triangles_.reserve(count);
    for (const int f : face_of_) triangles_.push_back(triangle_of(mesh, f));
    for (std::size_t begin = 0; begin < count;) {
      const int piece = piece_of(static_cast<std::size_t>(face_of_[begin]));
      std::size_t end = begin;
      while (end < count && piece_of(static_cast<std::size_t>(face_of_[end])) == piece) ++end;
      auto tree =
          std::make_unique<AabbTree>(triangles_.begin() + static_cast<std::ptrdiff_t>(begin),
                                     triangles_.begin() + static_cast<std::ptrdiff_t>(end));
      tree->accelerate_distance_queries();
      trees_.emplace(piece, std::move(tree));
      begin = end;
    }
  }

  /// The face of `piece` nearest p and its point nearest p; among every face when the
  /// piece has none (`piece` is ignored when the search has one piece only).
  std::pair<Point, int> nearest(const Point& p, int piece) const {
    const auto found = trees_.size() == 1 ? trees_.begin() : trees_.find(piece);
    if (found != trees_.end()) return on(*found->second, p);
    std::pair<Point, int> best;
    double best_distance_sq = std::numeric_limits<double>::infinity();
    for (const auto& entry : trees_) {
      const std::pair<Point, int> hit = on(*entry.second, p);
      const double distance_sq = CGAL::squared_distance(p, hit.first);
      if (distance_sq < best_distance_sq) {
        best_distance_sq = distance_sq;
        best = hit;
      }
    }
    return best;
  }

 private:
  std::pair<Point, int> on(const AabbTree& tree, const Point& p) const {
    const auto hit = tree.closest_point_and_primitive(p);
    return {hit.first, face_of_[static_cast<std::size_t>(hit.second - triangles_.begin())]};
  }

  std::vector<int> face_of_;         ///< per triangle, its face; ordered by piece
  std::vector<Triangle> triangles_;  ///< the faces, ordered by piece
  std::map<int, std::unique_ptr<AabbTree>> trees_;
};

/// Per face of `mesh`, the piece of its first corner in `vertex_piece`; empty when that is.
std::vector<int> face_pieces(const TriangleMesh& mesh, const std::vector<int>& vertex_piece) {
  std::vector<int> pieces;
  if (vertex_piece.empty()) return pieces;
  pieces.reserve(static_cast<std::size_t>(mesh.faces.rows()));
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    pieces.push_back(vertex_piece[static_cast<std::size_t>(mesh.faces(f, 0))]);
  return pieces;
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

/// A decimated garment, and per vertex the piece of the garment it stands for.
struct PiecewiseMesh {
  TriangleMesh mesh;
  std::vector<int> vertex_piece;
};

/// `piece` (a surface) decimated by edge collapses to `edge_ratio` of its edges
/// (Lindstrom–Turk; no collapse that turns a face's normal by more than a right angle or
/// leaves a sliver), or empty when CGAL cannot read it as a surface.
std::optional<TriangleMesh> decimate_piece(const TriangleMesh& piece, double edge_ratio) {
  std::vector<Point> points;
  points.reserve(static_cast<std::size_t>(piece.vertices.rows()));
  for (Eigen::Index v = 0; v < piece.vertices.rows(); ++v)
    points.push_back(point_of(piece.vertices, static_cast<int>(v)));
  std::vector<std::array<std::size_t, 3>> polygons;
  for (Eigen::Index f = 0; f < piece.faces.rows(); ++f)
    polygons.push_back({static_cast<std::size_t>(piece.faces(f, 0)),
                        static_cast<std::size_t>(piece.faces(f, 1)),
                        static_cast<std::size_t>(piece.faces(f, 2))});
  // Orienting splits the vertices where the faces around them do not form one fan, which
  // a halfedge mesh needs.
  PMP::orient_polygon_soup(points, polygons);
  if (!PMP::is_polygon_soup_a_polygon_mesh(polygons)) return std::nullopt;
  SurfaceMesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  SMS::Count_ratio_stop_predicate<SurfaceMesh> stop(edge_ratio);
  SMS::edge_collapse(
      mesh, stop,
      CGAL::parameters::filter(SMS::Bounded_normal_change_filter<KeepTriangleShapes>()));
  mesh.collect_garbage();

  TriangleMesh decimated;
  decimated.vertices.resize(static_cast<Eigen::Index>(mesh.number_of_vertices()), 3);
  for (const SurfaceMesh::Vertex_index v : mesh.vertices())
    decimated.vertices.row(static_cast<Eigen::Index>(v.idx())) =
        vector_of(mesh.point(v)).transpose();
  decimated.faces.resize(static_cast<Eigen::Index>(mesh.number_of_faces()), 3);
  Eigen::Index row = 0;
  for (const SurfaceMesh::Face_index f : mesh.faces()) {
    int k = 0;
    for (const SurfaceMesh::Vertex_index v : CGAL::vertices_around_face(mesh.halfedge(f), mesh))
      decimated.faces(row, k++) = static_cast<int>(v.idx());
    ++row;
  }
  return decimated;
}

/// The garment decimated to about `target_faces` faces, each piece on its own by the same
/// ratio (a collapse never joins two pieces, and the piece each proxy vertex stands for is
/// known), or empty when CGAL cannot read a piece as a surface.
/// @param vertex_piece vertex_pieces(garment).
std::optional<PiecewiseMesh> decimate(const TriangleMesh& garment,
                                      const std::vector<int>& vertex_piece, int target_faces) {
  const double edge_ratio =
      std::min(1.0, static_cast<double>(target_faces) / static_cast<double>(garment.faces.rows()));
  std::map<int, std::vector<int>> faces_of_piece;
  for (Eigen::Index f = 0; f < garment.faces.rows(); ++f)
    faces_of_piece[vertex_piece[static_cast<std::size_t>(garment.faces(f, 0))]].push_back(
        static_cast<int>(f));
  std::vector<TriangleMesh> parts;
  std::vector<int> part_piece;
  Eigen::Index vertex_count = 0, face_count = 0;
  std::vector<int> local(static_cast<std::size_t>(garment.vertices.rows()), -1);
  for (const auto& [piece, faces] : faces_of_piece) {
    // Vertices in the garment's order, so that a garment of one piece decimates as a whole.
    std::vector<int> used;
    for (const int f : faces)
      for (int c = 0; c < 3; ++c) {
        int& id = local[static_cast<std::size_t>(garment.faces(f, c))];
        if (id < 0) {
          id = 0;
          used.push_back(garment.faces(f, c));
        }
      }
    std::sort(used.begin(), used.end());
    TriangleMesh part;
    part.vertices.resize(static_cast<Eigen::Index>(used.size()), 3);
    for (std::size_t k = 0; k < used.size(); ++k) {
      local[static_cast<std::size_t>(used[k])] = static_cast<int>(k);
      part.vertices.row(static_cast<Eigen::Index>(k)) = garment.vertices.row(used[k]);
    }
    part.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
    for (std::size_t k = 0; k < faces.size(); ++k)
      for (int c = 0; c < 3; ++c)
        part.faces(static_cast<Eigen::Index>(k), c) =
            local[static_cast<std::size_t>(garment.faces(faces[k], c))];
    std::optional<TriangleMesh> decimated = decimate_piece(part, edge_ratio);
    if (!decimated) return std::nullopt;
    vertex_count += decimated->vertices.rows();
    face_count += decimated->faces.rows();
    parts.push_back(std::move(*decimated));
    part_piece.push_back(piece);
  }
  PiecewiseMesh out;
  out.mesh.vertices.resize(vertex_count, 3);
  out.mesh.faces.resize(face_count, 3);
  Eigen::Index vertex_row = 0, face_row = 0;
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const TriangleMesh& part = parts[k];
    out.mesh.vertices.middleRows(vertex_row, part.vertices.rows()) = part.vertices;
    out.mesh.faces.middleRows(face_row, part.faces.rows()) =
        part.faces.array() + static_cast<int>(vertex_row);
    out.vertex_piece.insert(out.vertex_piece.end(), static_cast<std::size_t>(part.vertices.rows()),
                            part_piece[k]);
    vertex_row += part.vertices.rows();
    face_row += part.faces.rows();
  }
  return out;
}

/// Per row of `points`, the nearest vertex of `surface` among the corners of the face of
/// the point's own piece nearest it.
/// @param point_piece per row of `points`, its piece; surface_piece: per vertex of surface.
std::vector<int> nearest_vertices(const MatrixX3d& points, const std::vector<int>& point_piece,
                                  const TriangleMesh& surface,
                                  const std::vector<int>& surface_piece) {
  const PieceFaceSearch search(surface, face_pieces(surface, surface_piece));
  std::vector<int> nearest(static_cast<std::size_t>(points.rows()));
  for (Eigen::Index v = 0; v < points.rows(); ++v) {
    const int f = search
                      .nearest(point_of(points, static_cast<int>(v)),
                               point_piece[static_cast<std::size_t>(v)])
                      .second;
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

SurfaceEmbedding::SurfaceEmbedding(const TriangleMesh& coarse, const MatrixX3d& fine_vertices,
                                   const std::vector<int>& coarse_vertex_piece,
                                   const std::vector<int>& fine_vertex_piece)
    : faces_(coarse.faces) {
  const PieceFaceSearch search(coarse, face_pieces(coarse, coarse_vertex_piece));
  placements_.resize(static_cast<std::size_t>(fine_vertices.rows()));
  for (Eigen::Index v = 0; v < fine_vertices.rows(); ++v) {
    const Vector3d x = fine_vertices.row(v).transpose();
    const int piece =
        fine_vertex_piece.empty() ? 0 : fine_vertex_piece[static_cast<std::size_t>(v)];
    const auto hit = search.nearest(Point(x.x(), x.y(), x.z()), piece);
    Placement& placement = placements_[static_cast<std::size_t>(v)];
    placement.face = hit.second;
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
  const std::vector<int> fine_piece = vertex_pieces(fine.garment);
  std::optional<PiecewiseMesh> decimated = decimate(fine.garment, fine_piece, target_faces);
  if (!decimated) {
    why_not = "the garment is not a surface CGAL's decimation can read";
    return std::nullopt;
  }
  TriangleMesh& coarse = decimated->mesh;
  if (!find_degenerate_faces(coarse).empty()) {
    why_not = "the decimated garment has degenerate faces";
    return std::nullopt;
  }
  const std::size_t self_crossings = find_self_intersecting_face_pairs(coarse, 0).pairs.count;
  const std::size_t avatar_crossings =
      find_intersecting_face_pairs(coarse, modelled_shrunk_avatar(fine), 0).count;
  if (self_crossings > 0 || avatar_crossings > 0) {
    why_not = fmt::format(
        "the decimated garment crosses itself in {} face pairs and the shrunk avatar in {}",
        self_crossings, avatar_crossings);
    return std::nullopt;
  }

  CoarseProxy proxy;
  proxy.fine_vertex =
      nearest_vertices(coarse.vertices, decimated->vertex_piece, fine.garment, fine_piece);
  proxy.embedding =
      SurfaceEmbedding(coarse, fine.garment.vertices, decimated->vertex_piece, fine_piece);
  proxy.clearance = proxy.embedding.max_offset() + kChordDepth * median_edge_length(fine.garment);
  proxy.edge_length = median_edge_length(coarse);
  GarmentScene& scene = proxy.scene;
  scene = fine;
  scene.garment = std::move(coarse);
  std::vector<bool> no_fit(static_cast<std::size_t>(fine.garment.vertices.rows()), false);
  for (const int v : fine.no_fit) no_fit[static_cast<std::size_t>(v)] = true;
  scene.no_fit.clear();
  scene.fit_offsets.clear();
  std::vector<char> skirt;
  for (std::size_t v = 0; v < proxy.fine_vertex.size(); ++v) {
    const auto nearest = static_cast<std::size_t>(proxy.fine_vertex[v]);
    if (no_fit[nearest]) scene.no_fit.push_back(static_cast<int>(v));
    if (!fine.fit_offsets.empty()) scene.fit_offsets.push_back(fine.fit_offsets[nearest]);
    if (fine.skeletons && !fine.skeletons->skirt_vertices.empty())
      skirt.push_back(fine.skeletons->skirt_vertices[nearest]);
  }
  if (scene.skeletons) scene.skeletons->skirt_vertices = std::move(skirt);
  return proxy;
}

}  // namespace gr
