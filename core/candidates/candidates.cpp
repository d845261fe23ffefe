#include "core/candidates/candidates.hpp"

#include <algorithm>
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

/// Avatar vertices that some contact face uses (a subset of faces may be modelled).
std::vector<int> used_avatar_points(const ContactMesh& mesh) {
  const int ng = mesh.garment_vertex_count;
  std::vector<char> used(static_cast<std::size_t>(mesh.avatar_vertex_count), 0);
  for (Eigen::Index f = 0; f < mesh.avatar_faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) used[static_cast<std::size_t>(mesh.avatar_faces(f, k) - ng)] = 1;
  std::vector<int> points;
  for (std::size_t i = 0; i < used.size(); ++i)
    if (used[i]) points.push_back(ng + static_cast<int>(i));
  return points;
}

/// Boxes of the vertices `ids` (or first, first + 1, ... when null), each grown by `grow`.
std::vector<Box> point_boxes(const std::vector<Box>& vertex_boxes, int first, int count,
                             const std::vector<int>* ids, double grow) {
  std::vector<Box> boxes(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    Box box = vertex_boxes[static_cast<std::size_t>(ids ? (*ids)[static_cast<std::size_t>(i)] : first + i)];
    box.min().array() -= grow;
    box.max().array() += grow;
    boxes[static_cast<std::size_t>(i)] = box;
  }
  return boxes;
}

bool same_boxes(const std::vector<Box>& a, const std::vector<Box>& b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](const Box& x, const Box& y) {
           return x.min() == y.min() && x.max() == y.max();
         });
}

}  // namespace

/// The avatar side's trees, kept while the avatar's vertex boxes and the radius stay the same.
struct CandidateFinder::AvatarTrees {
  std::vector<Box> vertex_boxes;
  double radius = -1.0;
  Bvh points, faces, edges;
};

CandidateFinder::CandidateFinder(ContactMesh mesh)
    : mesh_(std::move(mesh)), avatar_points_(used_avatar_points(mesh_)),
      avatar_trees_(std::make_unique<AvatarTrees>()) {}

CandidateFinder::~CandidateFinder() = default;

void CandidateFinder::check_positions(const Eigen::Ref<const MatrixX3d>& V) const {
  if (V.rows() != mesh_.vertex_count())
    throw std::invalid_argument("contact positions have " + std::to_string(V.rows()) +
                                " rows, the contact mesh has " + std::to_string(mesh_.vertex_count()) +
                                " vertices");
}

Candidates CandidateFinder::box_pairs(const std::vector<Box>& vertex_boxes, double radius) {
  const double grow = 0.5 * radius;
  const int ng = mesh_.garment_vertex_count;
  AvatarTrees& avatar = *avatar_trees_;
  std::vector<Box> avatar_vertex_boxes(vertex_boxes.begin() + ng, vertex_boxes.end());
  const bool rebuild_avatar = radius != avatar.radius || !same_boxes(avatar_vertex_boxes, avatar.vertex_boxes);
  if (rebuild_avatar) {
    avatar.vertex_boxes = std::move(avatar_vertex_boxes);
    avatar.radius = radius;
  }

  Bvh garment_points, garment_faces, garment_edges;
  tbb::parallel_invoke(
      [&] { garment_points.build(point_boxes(vertex_boxes, 0, ng, nullptr, grow)); },
      [&] { garment_faces.build(element_boxes(mesh_.garment_faces, vertex_boxes, grow)); },
      [&] { garment_edges.build(element_boxes(mesh_.garment_edges, vertex_boxes, grow)); },
      [&] {
        if (rebuild_avatar)
          avatar.points.build(point_boxes(vertex_boxes, 0, static_cast<int>(avatar_points_.size()),
                                          &avatar_points_, grow));
      },
      [&] { if (rebuild_avatar) avatar.faces.build(element_boxes(mesh_.avatar_faces, vertex_boxes, grow)); },
      [&] { if (rebuild_avatar) avatar.edges.build(element_boxes(mesh_.avatar_edges, vertex_boxes, grow)); });

  const auto& gf = mesh_.garment_faces;
  const auto& af = mesh_.avatar_faces;
  const auto& ge = mesh_.garment_edges;
  const auto& ae = mesh_.avatar_edges;
  const bool self_contact = mesh_.self_contact;
  using PT = PointTriangleCandidate;
  using EE = EdgeEdgeCandidate;
  Candidates out;
  std::vector<PT> garment_avatar, self_pt, avatar_garment;
  std::vector<EE> edges_ga, self_ee;
  tbb::parallel_invoke(
      [&] {
        garment_avatar = garment_points.collect_pairs<PT>(
            avatar.faces, [&](int v, int f, std::vector<PT>& sink) { sink.push_back({v, face(af, f)}); });
      },
      [&] {
        avatar_garment = avatar.points.collect_pairs<PT>(garment_faces, [&](int i, int f, std::vector<PT>& sink) {
          sink.push_back({avatar_points_[static_cast<std::size_t>(i)], face(gf, f)});
        });
      },
      [&] {
        edges_ga = garment_edges.collect_pairs<EE>(
            avatar.edges, [&](int a, int b, std::vector<EE>& sink) { sink.push_back({edge(ge, a), edge(ae, b)}); });
      },
      [&] {
        if (!self_contact) return;
        self_pt = garment_points.collect_pairs<PT>(garment_faces, [&](int v, int f, std::vector<PT>& sink) {
          if (gf(f, 0) != v && gf(f, 1) != v && gf(f, 2) != v) sink.push_back({v, face(gf, f)});
        });
      },
      [&] {
        if (!self_contact) return;
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

Candidates CandidateFinder::find(const Eigen::Ref<const MatrixX3d>& V, double inflation_radius) {
  check_positions(V);
  std::vector<Box> vertex_boxes(static_cast<std::size_t>(V.rows()));
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    const Vector3d p = V.row(i).transpose();
    vertex_boxes[static_cast<std::size_t>(i)] = Box(p, p);
  }
  if (inflation_radius <= swept_radius_ && inside_swept_boxes(vertex_boxes))
    return filter_swept(vertex_boxes, inflation_radius);
  return box_pairs(vertex_boxes, inflation_radius);
}

Candidates CandidateFinder::find_swept(const Eigen::Ref<const MatrixX3d>& V0,
                                       const Eigen::Ref<const MatrixX3d>& V1, double inflation_radius) {
  check_positions(V0);
  check_positions(V1);
  std::vector<Box> vertex_boxes(static_cast<std::size_t>(V0.rows()));
  for (Eigen::Index i = 0; i < V0.rows(); ++i) {
    const Vector3d p = V0.row(i).transpose(), q = V1.row(i).transpose();
    vertex_boxes[static_cast<std::size_t>(i)] = Box(p.cwiseMin(q), p.cwiseMax(q));
  }
  swept_ = box_pairs(vertex_boxes, inflation_radius);
  swept_boxes_ = std::move(vertex_boxes);
  swept_radius_ = inflation_radius;
  return swept_;
}

bool CandidateFinder::inside_swept_boxes(const std::vector<Box>& vertex_boxes) const {
  if (swept_boxes_.size() != vertex_boxes.size()) return false;
  for (std::size_t i = 0; i < vertex_boxes.size(); ++i)
    if (!swept_boxes_[i].contains(vertex_boxes[i])) return false;
  return true;
}

Candidates CandidateFinder::filter_swept(const std::vector<Box>& vertex_boxes, double radius) const {
  // The same test as the tree search, on exact boxes: the pair's two element boxes, each
  // grown by radius / 2, overlap.
  const auto box_of = [&](const int* ids, int count) {
    Box box = vertex_boxes[static_cast<std::size_t>(ids[0])];
    for (int k = 1; k < count; ++k) box.extend(vertex_boxes[static_cast<std::size_t>(ids[k])]);
    box.min().array() -= 0.5 * radius;
    box.max().array() += 0.5 * radius;
    return box;
  };
  const std::size_t npt = swept_.point_triangle.size();
  std::vector<char> keep(swept_.size(), 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, keep.size(), 1024), [&](const auto& range) {
    for (std::size_t k = range.begin(); k != range.end(); ++k) {
      if (k < npt) {
        const PointTriangleCandidate& c = swept_.point_triangle[k];
        keep[k] = box_of(&c.point, 1).intersects(box_of(c.triangle.data(), 3));
      } else {
        const EdgeEdgeCandidate& c = swept_.edge_edge[k - npt];
        keep[k] = box_of(c.edge_a.data(), 2).intersects(box_of(c.edge_b.data(), 2));
      }
    }
  });
  Candidates out;
  for (std::size_t k = 0; k < npt; ++k)
    if (keep[k]) out.point_triangle.push_back(swept_.point_triangle[k]);
  for (std::size_t k = npt; k < keep.size(); ++k)
    if (keep[k]) out.edge_edge.push_back(swept_.edge_edge[k - npt]);
  return out;
}

Candidates find_candidates(const ContactMesh& mesh, const Eigen::Ref<const MatrixX3d>& V,
                           double inflation_radius) {
  return CandidateFinder(mesh).find(V, inflation_radius);
}

Candidates find_swept_candidates(const ContactMesh& mesh, const Eigen::Ref<const MatrixX3d>& V0,
                                 const Eigen::Ref<const MatrixX3d>& V1, double inflation_radius) {
  return CandidateFinder(mesh).find_swept(V0, V1, inflation_radius);
}

}  // namespace gr
