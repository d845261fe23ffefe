#include "core/candidates/candidates.hpp"

#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "core/broad_phase/bvh.hpp"

namespace gr {
namespace {

using Box = Eigen::AlignedBox3d;

/// Boxes of elements (rows of vertex ids) over their vertices' boxes, each grown by `grow`.
template <typename Elements>
std::vector<Box> element_boxes(const Elements& elements, const std::vector<Box>& vertex_boxes, double grow) {
  std::vector<Box> boxes(static_cast<std::size_t>(elements.rows()));
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, elements.rows(), 2048), [&](const auto& range) {
    for (Eigen::Index e = range.begin(); e != range.end(); ++e) {
      Box box = vertex_boxes[static_cast<std::size_t>(elements(e, 0))];
      for (Eigen::Index k = 1; k < elements.cols(); ++k) box.extend(vertex_boxes[static_cast<std::size_t>(elements(e, k))]);
      box.min().array() -= grow;
      box.max().array() += grow;
      boxes[static_cast<std::size_t>(e)] = box;
    }
  });
  return boxes;
}

std::array<int, 3> face(const MatrixX3i& faces, int f) { return {faces(f, 0), faces(f, 1), faces(f, 2)}; }
std::array<int, 2> edge(const MatrixX2i& edges, int e) { return {edges(e, 0), edges(e, 1)}; }

/// The pairs whose element boxes (over each vertex's box: a point, or a swept segment)
/// come within `radius`: every box grows by radius / 2, one tree per element set, and the
/// trees are searched against each other.
Candidates find_box_pairs(const ContactMesh& mesh, const std::vector<Box>& vertex_boxes, double radius) {
  const double grow = 0.5 * radius;
  const int ng = mesh.garment_vertex_count;
  // Avatar vertices that some contact face uses (a subset of faces may be modelled).
  std::vector<int> avatar_points;
  {
    std::vector<char> used(static_cast<std::size_t>(mesh.avatar_vertex_count), 0);
    for (Eigen::Index f = 0; f < mesh.avatar_faces.rows(); ++f)
      for (int k = 0; k < 3; ++k) used[static_cast<std::size_t>(mesh.avatar_faces(f, k) - ng)] = 1;
    for (std::size_t i = 0; i < used.size(); ++i)
      if (used[i]) avatar_points.push_back(ng + static_cast<int>(i));
  }
  const auto point_boxes = [&](int first, int count, const std::vector<int>* ids) {
    std::vector<Box> boxes(static_cast<std::size_t>(count));
    for (int i = 0; i < count; ++i) {
      Box box = vertex_boxes[static_cast<std::size_t>(ids ? (*ids)[static_cast<std::size_t>(i)] : first + i)];
      box.min().array() -= grow;
      box.max().array() += grow;
      boxes[static_cast<std::size_t>(i)] = box;
    }
    return boxes;
  };

  Bvh garment_points, avatar_points_tree, garment_faces, avatar_faces, garment_edges, avatar_edges;
  tbb::parallel_invoke(
      [&] { garment_points.build(point_boxes(0, ng, nullptr)); },
      [&] { avatar_points_tree.build(point_boxes(0, static_cast<int>(avatar_points.size()), &avatar_points)); },
      [&] { garment_faces.build(element_boxes(mesh.garment_faces, vertex_boxes, grow)); },
      [&] { avatar_faces.build(element_boxes(mesh.avatar_faces, vertex_boxes, grow)); },
      [&] { garment_edges.build(element_boxes(mesh.garment_edges, vertex_boxes, grow)); },
      [&] { avatar_edges.build(element_boxes(mesh.avatar_edges, vertex_boxes, grow)); });

  const auto& gf = mesh.garment_faces;
  const auto& af = mesh.avatar_faces;
  const auto& ge = mesh.garment_edges;
  const auto& ae = mesh.avatar_edges;
  using PT = PointTriangleCandidate;
  using EE = EdgeEdgeCandidate;
  Candidates out;
  std::vector<PT> garment_avatar, self_pt, avatar_garment;
  std::vector<EE> edges_ga, self_ee;
  tbb::parallel_invoke(
      [&] {
        garment_avatar = garment_points.collect_pairs<PT>(
            avatar_faces, [&](int v, int f, std::vector<PT>& sink) { sink.push_back({v, face(af, f)}); });
      },
      [&] {
        avatar_garment = avatar_points_tree.collect_pairs<PT>(garment_faces, [&](int i, int f, std::vector<PT>& sink) {
          sink.push_back({avatar_points[static_cast<std::size_t>(i)], face(gf, f)});
        });
      },
      [&] {
        edges_ga = garment_edges.collect_pairs<EE>(
            avatar_edges, [&](int a, int b, std::vector<EE>& sink) { sink.push_back({edge(ge, a), edge(ae, b)}); });
      },
      [&] {
        if (!mesh.self_contact) return;
        self_pt = garment_points.collect_pairs<PT>(garment_faces, [&](int v, int f, std::vector<PT>& sink) {
          if (gf(f, 0) != v && gf(f, 1) != v && gf(f, 2) != v) sink.push_back({v, face(gf, f)});
        });
      },
      [&] {
        if (!mesh.self_contact) return;
        self_ee = garment_edges.collect_pairs<EE>(garment_edges, [&](int a, int b, std::vector<EE>& sink) {
          const int a0 = ge(a, 0), a1 = ge(a, 1), b0 = ge(b, 0), b1 = ge(b, 1);
          if (a0 != b0 && a0 != b1 && a1 != b0 && a1 != b1) sink.push_back({{a0, a1}, {b0, b1}});
        });
      });
  out.point_triangle = std::move(garment_avatar);
  out.point_triangle.insert(out.point_triangle.end(), self_pt.begin(), self_pt.end());
  out.point_triangle.insert(out.point_triangle.end(), avatar_garment.begin(), avatar_garment.end());
  out.edge_edge = std::move(edges_ga);
  out.edge_edge.insert(out.edge_edge.end(), self_ee.begin(), self_ee.end());
  return out;
}

void check_positions(const ContactMesh& mesh, const Eigen::Ref<const MatrixX3d>& V) {
  if (V.rows() != mesh.vertex_count())
    throw std::invalid_argument("contact positions have " + std::to_string(V.rows()) +
                                " rows, the contact mesh has " + std::to_string(mesh.vertex_count()) +
                                " vertices");
}

}  // namespace

Candidates find_candidates(const ContactMesh& mesh, const Eigen::Ref<const MatrixX3d>& V,
                           double inflation_radius) {
  check_positions(mesh, V);
  std::vector<Box> vertex_boxes(static_cast<std::size_t>(V.rows()));
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    const Vector3d p = V.row(i).transpose();
    vertex_boxes[static_cast<std::size_t>(i)] = Box(p, p);
  }
  return find_box_pairs(mesh, vertex_boxes, inflation_radius);
}

Candidates find_swept_candidates(const ContactMesh& mesh, const Eigen::Ref<const MatrixX3d>& V0,
                                 const Eigen::Ref<const MatrixX3d>& V1, double inflation_radius) {
  check_positions(mesh, V0);
  check_positions(mesh, V1);
  std::vector<Box> vertex_boxes(static_cast<std::size_t>(V0.rows()));
  for (Eigen::Index i = 0; i < V0.rows(); ++i) {
    const Vector3d p = V0.row(i).transpose(), q = V1.row(i).transpose();
    vertex_boxes[static_cast<std::size_t>(i)] = Box(p.cwiseMin(q), p.cwiseMax(q));
  }
  return find_box_pairs(mesh, vertex_boxes, inflation_radius);
}

}  // namespace gr
