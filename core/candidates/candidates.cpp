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

/// Query elements per parallel task; results are joined in task order, so the candidate
/// lists come out the same on any thread count.
constexpr std::size_t kQueryChunk = 256;

/// Runs `query(i, sink)` for i in [0, n) in parallel chunks and appends the sinks to
/// `out` in index order.
template <typename T, typename Query>
void collect(std::size_t n, std::vector<T>& out, const Query& query) {
  const std::size_t chunks = (n + kQueryChunk - 1) / kQueryChunk;
  std::vector<std::vector<T>> parts(chunks);
  tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t c) {
    const std::size_t end = std::min(n, (c + 1) * kQueryChunk);
    for (std::size_t i = c * kQueryChunk; i < end; ++i) query(i, parts[c]);
  });
  std::size_t total = out.size();
  for (const auto& part : parts) total += part.size();
  out.reserve(total);
  for (const auto& part : parts) out.insert(out.end(), part.begin(), part.end());
}

/// Box of each element (a row of vertex ids) over its vertices' boxes, grown by `radius`.
template <typename Elements>
std::vector<Box> element_boxes(const Elements& elements, const std::vector<Box>& vertex_boxes,
                               double radius) {
  std::vector<Box> boxes(static_cast<std::size_t>(elements.rows()));
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, elements.rows(), 1024), [&](const auto& range) {
    for (Eigen::Index e = range.begin(); e != range.end(); ++e) {
      Box box = vertex_boxes[static_cast<std::size_t>(elements(e, 0))];
      for (Eigen::Index k = 1; k < elements.cols(); ++k)
        box.extend(vertex_boxes[static_cast<std::size_t>(elements(e, k))]);
      box.min().array() -= radius;
      box.max().array() += radius;
      boxes[static_cast<std::size_t>(e)] = box;
    }
  });
  return boxes;
}

Box edge_box(const MatrixX2i& edges, Eigen::Index e, const std::vector<Box>& vertex_boxes) {
  return vertex_boxes[static_cast<std::size_t>(edges(e, 0))].merged(
      vertex_boxes[static_cast<std::size_t>(edges(e, 1))]);
}

bool edges_share_vertex(const MatrixX2i& edges, Eigen::Index a, Eigen::Index b) {
  return edges(a, 0) == edges(b, 0) || edges(a, 0) == edges(b, 1) || edges(a, 1) == edges(b, 0) ||
         edges(a, 1) == edges(b, 1);
}

/// The pairs whose element boxes (each vertex's box, e.g. a point or a swept segment)
/// come within `radius`: trees over faces and edges grown by the radius, queried with the
/// other side's plain boxes.
Candidates find_box_pairs(const ContactMesh& mesh, const std::vector<Box>& vertex_boxes,
                          double radius) {
  Bvh avatar_faces, garment_faces, avatar_edges, garment_edges;
  tbb::parallel_invoke(
      [&] { avatar_faces.build(element_boxes(mesh.avatar_faces, vertex_boxes, radius)); },
      [&] { garment_faces.build(element_boxes(mesh.garment_faces, vertex_boxes, radius)); },
      [&] { avatar_edges.build(element_boxes(mesh.avatar_edges, vertex_boxes, radius)); },
      [&] {
        if (mesh.self_contact) garment_edges.build(element_boxes(mesh.garment_edges, vertex_boxes, radius));
      });

  Candidates out;
  const auto& gf = mesh.garment_faces;
  const auto& af = mesh.avatar_faces;
  const auto face = [](const MatrixX3i& faces, int f) {
    return std::array<int, 3>{faces(f, 0), faces(f, 1), faces(f, 2)};
  };
  // Garment vertices against avatar triangles and, for self-contact, against garment
  // triangles they are not a corner of.
  collect(static_cast<std::size_t>(mesh.garment_vertex_count), out.point_triangle,
          [&](std::size_t i, std::vector<PointTriangleCandidate>& sink) {
            const int v = static_cast<int>(i);
            const Box& box = vertex_boxes[i];
            avatar_faces.query(box, [&](int f) { sink.push_back({v, face(af, f)}); });
            if (!mesh.self_contact) return;
            garment_faces.query(box, [&](int f) {
              if (gf(f, 0) != v && gf(f, 1) != v && gf(f, 2) != v) sink.push_back({v, face(gf, f)});
            });
          });
  // Avatar vertices that some contact face uses, against garment triangles.
  std::vector<char> used(static_cast<std::size_t>(mesh.avatar_vertex_count), 0);
  for (Eigen::Index f = 0; f < af.rows(); ++f)
    for (int k = 0; k < 3; ++k) used[static_cast<std::size_t>(af(f, k) - mesh.garment_vertex_count)] = 1;
  collect(used.size(), out.point_triangle, [&](std::size_t i, std::vector<PointTriangleCandidate>& sink) {
    if (!used[i]) return;
    const int v = mesh.garment_vertex_count + static_cast<int>(i);
    garment_faces.query(vertex_boxes[static_cast<std::size_t>(v)],
                        [&](int f) { sink.push_back({v, face(gf, f)}); });
  });
  // Garment edges against avatar edges and, for self-contact, later garment edges that
  // share no vertex (each unordered pair once).
  const auto& ge = mesh.garment_edges;
  const auto& ae = mesh.avatar_edges;
  collect(static_cast<std::size_t>(ge.rows()), out.edge_edge,
          [&](std::size_t i, std::vector<EdgeEdgeCandidate>& sink) {
            const auto e = static_cast<Eigen::Index>(i);
            const Box box = edge_box(ge, e, vertex_boxes);
            const std::array<int, 2> a{ge(e, 0), ge(e, 1)};
            avatar_edges.query(box, [&](int f) { sink.push_back({a, {ae(f, 0), ae(f, 1)}}); });
            if (!mesh.self_contact) return;
            garment_edges.query(box, [&](int f) {
              if (f > e && !edges_share_vertex(ge, e, f)) sink.push_back({a, {ge(f, 0), ge(f, 1)}});
            });
          });
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
