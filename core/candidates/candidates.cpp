#include "core/candidates/candidates.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "core/broad_phase/bvh.hpp"
#include "core/broad_phase/pair_separation.hpp"
#include "core/broad_phase/refitted_tree.hpp"
#include "core/candidates/self_contact_search.hpp"
#include "core/distance/edge_edge_distance.hpp"
#include "core/distance/point_triangle_distance.hpp"

namespace gr {

std::array<int, 5> self_pair_key(const PointTriangleCandidate& pair) {
  std::array<int, 3> t = pair.triangle;
  std::sort(t.begin(), t.end());
  return {0, pair.point, t[0], t[1], t[2]};
}

std::array<int, 5> self_pair_key(const EdgeEdgeCandidate& pair) {
  std::array<int, 2> a{std::min(pair.edge_a[0], pair.edge_a[1]),
                       std::max(pair.edge_a[0], pair.edge_a[1])};
  std::array<int, 2> b{std::min(pair.edge_b[0], pair.edge_b[1]),
                       std::max(pair.edge_b[0], pair.edge_b[1])};
  if (b < a) std::swap(a, b);
  return {1, a[0], a[1], b[0], b[1]};
}

namespace {

/// Leaves out the self pairs that are not modelled (ContactMesh::unmodelled_self_pairs).
void drop_unmodelled_pairs(const std::vector<std::array<int, 5>>& unmodelled,
                           std::vector<PointTriangleCandidate>& pt,
                           std::vector<EdgeEdgeCandidate>& ee) {
  if (unmodelled.empty()) return;
  const auto listed = [&](const std::array<int, 5>& key) {
    return std::binary_search(unmodelled.begin(), unmodelled.end(), key);
  };
  pt.erase(
      std::remove_if(pt.begin(), pt.end(),
                     [&](const PointTriangleCandidate& c) { return listed(self_pair_key(c)); }),
      pt.end());
  ee.erase(std::remove_if(ee.begin(), ee.end(),
                          [&](const EdgeEdgeCandidate& c) { return listed(self_pair_key(c)); }),
           ee.end());
}

using Box = Eigen::AlignedBox3d;

/// Boxes of elements (rows of vertex ids) over their vertices' boxes, each grown by `grow`.
template <typename Elements>
std::vector<Box> element_boxes(const Elements& elements, const std::vector<Box>& vertex_boxes,
                               double grow) {
  std::vector<Box> boxes(static_cast<std::size_t>(elements.rows()));
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, elements.rows(), 2048),
                    [&](const auto& range) {
                      for (Eigen::Index e = range.begin(); e != range.end(); ++e) {
                        Box box = vertex_boxes[static_cast<std::size_t>(elements(e, 0))];
                        for (Eigen::Index k = 1; k < elements.cols(); ++k)
                          box.extend(vertex_boxes[static_cast<std::size_t>(elements(e, k))]);
                        box.min().array() -= grow;
                        box.max().array() += grow;
                        boxes[static_cast<std::size_t>(e)] = box;
                      }
                    });
  return boxes;
}

std::array<int, 3> face(const MatrixX3i& faces, int f) {
  return {faces(f, 0), faces(f, 1), faces(f, 2)};
}
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
    Box box = vertex_boxes[static_cast<std::size_t>(ids ? (*ids)[static_cast<std::size_t>(i)]
                                                        : first + i)];
    box.min().array() -= grow;
    box.max().array() += grow;
    boxes[static_cast<std::size_t>(i)] = box;
  }
  return boxes;
}

/// How far (normalized units) a static query's vertex may lie off its segment of the last
/// swept motion and still count as on it: line-search points x + alpha dx differ from the
/// exact segment by rounding only, far below this.
constexpr double kOnMotionTolerance = 1e-10;

bool same_boxes(const std::vector<Box>& a, const std::vector<Box>& b) {
  return a.size() == b.size() &&
         std::equal(a.begin(), a.end(), b.begin(), [](const Box& x, const Box& y) {
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

/// The garment's trees (see RefittedTree).
struct CandidateFinder::GarmentTrees {
  RefittedTree points, faces, edges;
};

CandidateFinder::CandidateFinder(ContactMesh mesh)
    : mesh_(std::move(mesh)), avatar_points_(used_avatar_points(mesh_)),
      avatar_trees_(std::make_unique<AvatarTrees>()),
      garment_trees_(std::make_unique<GarmentTrees>()) {}

CandidateFinder::~CandidateFinder() = default;

const GarmentRegions* CandidateFinder::regions() const {
  return self_ ? &self_->regions() : nullptr;
}

const std::vector<char>& CandidateFinder::fold_free() const {
  static const std::vector<char> none;
  return self_ ? self_->fold_free() : none;
}

void CandidateFinder::check_positions(const Eigen::Ref<const MatrixX3d>& V) const {
  if (V.rows() != mesh_.vertex_count())
    throw std::invalid_argument("contact positions have " + std::to_string(V.rows()) +
                                " rows, the contact mesh has " +
                                std::to_string(mesh_.vertex_count()) + " vertices");
}

Candidates CandidateFinder::box_pairs(const std::vector<Box>& vertex_boxes, double radius,
                                      const Eigen::Ref<const MatrixX3d>& V0,
                                      const Eigen::Ref<const MatrixX3d>& V1, double threshold) {
  const double grow = 0.5 * radius;
  const int ng = mesh_.garment_vertex_count;
  AvatarTrees& avatar = *avatar_trees_;
  std::vector<Box> avatar_vertex_boxes(vertex_boxes.begin() + ng, vertex_boxes.end());
  const bool rebuild_avatar =
      radius != avatar.radius || !same_boxes(avatar_vertex_boxes, avatar.vertex_boxes);
  if (rebuild_avatar) {
    avatar.vertex_boxes = std::move(avatar_vertex_boxes);
    avatar.radius = radius;
  }

  std::vector<Box> garment_point_boxes, garment_face_boxes, garment_edge_boxes;
  tbb::parallel_invoke(
      [&] { garment_point_boxes = point_boxes(vertex_boxes, 0, ng, nullptr, grow); },
      [&] { garment_face_boxes = element_boxes(mesh_.garment_faces, vertex_boxes, grow); },
      [&] { garment_edge_boxes = element_boxes(mesh_.garment_edges, vertex_boxes, grow); });
  GarmentTrees& garment = *garment_trees_;
  const Bvh& garment_points = garment.points.tree;
  const Bvh& garment_faces = garment.faces.tree;
  const Bvh& garment_edges = garment.edges.tree;
  tbb::parallel_invoke(
      [&] { garment.points.update(garment_point_boxes); },
      [&] { garment.faces.update(garment_face_boxes); },
      [&] { garment.edges.update(garment_edge_boxes); },
      [&] {
        if (rebuild_avatar)
          avatar.points.build(point_boxes(vertex_boxes, 0, static_cast<int>(avatar_points_.size()),
                                          &avatar_points_, grow));
      },
      [&] {
        if (rebuild_avatar)
          avatar.faces.build(element_boxes(mesh_.avatar_faces, vertex_boxes, grow));
      },
      [&] {
        if (rebuild_avatar)
          avatar.edges.build(element_boxes(mesh_.avatar_edges, vertex_boxes, grow));
      });

  const auto& gf = mesh_.garment_faces;
  const auto& af = mesh_.avatar_faces;
  const auto& ge = mesh_.garment_edges;
  const auto& ae = mesh_.avatar_edges;
  const bool self_contact = mesh_.self_contact;
  using PT = PointTriangleCandidate;
  using EE = EdgeEdgeCandidate;
  // Box overlap is a loose test for pairs of neighbours in one mesh and for tilted layers;
  // pairs whose separation bound already rules them out are not emitted.
  const auto keep_pt = [&](int v, const std::array<int, 3>& t) {
    return pair_may_come_within(V0, V1, {v, t[0], t[1], t[2]}, 1, threshold);
  };
  const auto keep_ee = [&](const std::array<int, 2>& a, const std::array<int, 2>& b) {
    return pair_may_come_within(V0, V1, {a[0], a[1], b[0], b[1]}, 2, threshold);
  };
  const auto meets_avatar = [](const std::vector<char>& mask, int element) {
    return mask.empty() || mask[static_cast<std::size_t>(element)] != 0;
  };
  const auto& point_meets = mesh_.garment_point_meets_avatar;
  const auto& edge_meets = mesh_.garment_edge_meets_avatar;
  const auto& face_meets = mesh_.garment_face_meets_avatar;
  Candidates out;
  std::vector<PT> garment_avatar, self_pt, avatar_garment;
  std::vector<EE> edges_ga, self_ee;
  tbb::parallel_invoke(
      [&] {
        garment_avatar = garment_points.collect_pairs<PT>(
            avatar.faces, [&](int v, int f, std::vector<PT>& sink) {
              if (meets_avatar(point_meets, v) && keep_pt(v, face(af, f)))
                sink.push_back({v, face(af, f)});
            });
      },
      [&] {
        avatar_garment = avatar.points.collect_pairs<PT>(
            garment_faces, [&](int i, int f, std::vector<PT>& sink) {
              const int v = avatar_points_[static_cast<std::size_t>(i)];
              if (meets_avatar(face_meets, f) && keep_pt(v, face(gf, f)))
                sink.push_back({v, face(gf, f)});
            });
      },
      [&] {
        edges_ga =
            garment_edges.collect_pairs<EE>(avatar.edges, [&](int a, int b, std::vector<EE>& sink) {
              if (meets_avatar(edge_meets, a) && keep_ee(edge(ge, a), edge(ae, b)))
                sink.push_back({edge(ge, a), edge(ae, b)});
            });
      },
      [&] {
        if (!self_contact) return;
        if (!self_)
          self_ =
              std::make_unique<SelfContactSearch>(mesh_, V0.topRows(mesh_.garment_vertex_count));
        self_->find(garment_point_boxes, garment_face_boxes, garment_edge_boxes, V0, V1, threshold,
                    self_pt, self_ee);
        drop_unmodelled_pairs(mesh_.unmodelled_self_pairs, self_pt, self_ee);
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
  if (inflation_radius <= swept_radius_ && on_swept_motion(V))
    return filter_swept(V, inflation_radius);
  return box_pairs(vertex_boxes, inflation_radius, V, V, inflation_radius);
}

Candidates CandidateFinder::find_swept(const Eigen::Ref<const MatrixX3d>& V0,
                                       const Eigen::Ref<const MatrixX3d>& V1,
                                       double inflation_radius) {
  check_positions(V0);
  check_positions(V1);
  std::vector<Box> vertex_boxes(static_cast<std::size_t>(V0.rows()));
  for (Eigen::Index i = 0; i < V0.rows(); ++i) {
    const Vector3d p = V0.row(i).transpose(), q = V1.row(i).transpose();
    // Grown by the tolerance of on_swept_motion, so that the list also serves static
    // queries that lie on the motion only up to rounding.
    vertex_boxes[static_cast<std::size_t>(i)] =
        Box(p.cwiseMin(q).array() - kOnMotionTolerance, p.cwiseMax(q).array() + kOnMotionTolerance);
  }
  // A static query on this motion may be off it by rounding (kOnMotionTolerance per
  // vertex), which can shrink a pair's gap by twice that: keep pairs that come that close.
  swept_ = box_pairs(vertex_boxes, inflation_radius, V0, V1,
                     inflation_radius + 2.0 * kOnMotionTolerance);
  if (self_ && mesh_.garment_faces.rows() > 0) {
    ++swept_queries_;
    fold_free_fraction_sum_ += static_cast<double>(self_->fold_free_faces()) /
                               static_cast<double>(mesh_.garment_faces.rows());
  }
  swept_start_ = V0;
  swept_end_ = V1;
  swept_radius_ = inflation_radius;
  return swept_;
}

bool CandidateFinder::on_swept_motion(const Eigen::Ref<const MatrixX3d>& V) const {
  if (swept_start_.rows() != V.rows()) return false;
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    const Vector3d a = swept_start_.row(i).transpose(), d = swept_end_.row(i).transpose() - a;
    const Vector3d p = V.row(i).transpose() - a;
    const double length_sq = d.squaredNorm();
    const double s = length_sq > 0.0 ? std::clamp(p.dot(d) / length_sq, 0.0, 1.0) : 0.0;
    if ((p - s * d).squaredNorm() > kOnMotionTolerance * kOnMotionTolerance) return false;
  }
  return true;
}

Candidates CandidateFinder::filter_swept(const Eigen::Ref<const MatrixX3d>& V,
                                         double radius) const {
  // Every pair that may be within the radius at V is in the swept list (V is on the swept
  // motion): keep those whose separation bound at V does not rule them out.
  const std::size_t npt = swept_.point_triangle.size();
  std::vector<char> keep(swept_.size(), 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, keep.size(), 1024), [&](const auto& range) {
    for (std::size_t k = range.begin(); k != range.end(); ++k) {
      if (k < npt) {
        const PointTriangleCandidate& c = swept_.point_triangle[k];
        keep[k] = pair_may_come_within(V, V, {c.point, c.triangle[0], c.triangle[1], c.triangle[2]},
                                       1, radius);
      } else {
        const EdgeEdgeCandidate& c = swept_.edge_edge[k - npt];
        keep[k] = pair_may_come_within(V, V, {c.edge_a[0], c.edge_a[1], c.edge_b[0], c.edge_b[1]},
                                       2, radius);
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

namespace {

/// The self pairs of the garment alone closer than `gap` at `garment` for which `keep`
/// holds, as sorted keys.
template <typename KeepPointTriangle, typename KeepEdgeEdge>
std::vector<std::array<int, 5>> self_pairs_closer_than(const ContactMesh& mesh,
                                                       const Eigen::Ref<const MatrixX3d>& garment,
                                                       double gap, KeepPointTriangle keep_pt,
                                                       KeepEdgeEdge keep_ee) {
  ContactMesh self = mesh;
  self.avatar_vertex_count = 0;
  self.avatar_faces.resize(0, 3);
  self.avatar_edges.resize(0, 2);
  self.cull_fold_free = false;
  self.unmodelled_self_pairs.clear();
  const Candidates near = find_candidates(self, garment, gap);
  const auto at = [&](int v) -> Vector3d { return garment.row(v).transpose(); };
  const double gap_sq = gap * gap;
  std::vector<std::array<int, 5>> keys;
  for (const PointTriangleCandidate& c : near.point_triangle)
    if (keep_pt(c) && point_triangle_distance_sq(at(c.point), at(c.triangle[0]), at(c.triangle[1]),
                                                 at(c.triangle[2])) < gap_sq)
      keys.push_back(self_pair_key(c));
  for (const EdgeEdgeCandidate& c : near.edge_edge)
    if (keep_ee(c) && edge_edge_distance_sq(at(c.edge_a[0]), at(c.edge_a[1]), at(c.edge_b[0]),
                                            at(c.edge_b[1])) < gap_sq)
      keys.push_back(self_pair_key(c));
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  return keys;
}

}  // namespace

std::vector<std::array<int, 5>> crossing_pairs_closer_than(
    const ContactMesh& mesh, const Eigen::Ref<const MatrixX3d>& garment, double gap,
    const std::vector<std::array<int, 2>>& same_place) {
  const std::vector<std::array<int, 2>>& crossing = mesh.garment_crossing_faces;
  if ((crossing.empty() && same_place.empty()) || !mesh.self_contact) return {};
  std::vector<int> place(static_cast<std::size_t>(mesh.garment_vertex_count));
  std::iota(place.begin(), place.end(), 0);
  for (const auto& [a, b] : same_place) {
    const int root =
        std::min(place[static_cast<std::size_t>(a)], place[static_cast<std::size_t>(b)]);
    place[static_cast<std::size_t>(a)] = place[static_cast<std::size_t>(b)] = root;
  }
  const auto tied = [&](std::initializer_list<int> first, std::initializer_list<int> second) {
    if (same_place.empty()) return false;
    for (const int u : first)
      for (const int v : second)
        if (place[static_cast<std::size_t>(u)] == place[static_cast<std::size_t>(v)]) return true;
    return false;
  };
  std::vector<std::vector<int>> faces_of(static_cast<std::size_t>(mesh.garment_vertex_count));
  for (Eigen::Index f = 0; f < mesh.garment_faces.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      faces_of[static_cast<std::size_t>(mesh.garment_faces(f, k))].push_back(static_cast<int>(f));
  const auto holding = [&](std::initializer_list<int> vertices) {
    std::vector<int> faces;
    for (const int f : faces_of[static_cast<std::size_t>(*vertices.begin())]) {
      bool all = true;
      for (const int v : vertices)
        all = all && (mesh.garment_faces(f, 0) == v || mesh.garment_faces(f, 1) == v ||
                      mesh.garment_faces(f, 2) == v);
      if (all) faces.push_back(f);
    }
    return faces;
  };
  const auto all_cross = [&](const std::vector<int>& a, const std::vector<int>& b) {
    if (a.empty() || b.empty()) return false;
    for (const int f : a)
      for (const int g : b)
        if (!std::binary_search(crossing.begin(), crossing.end(),
                                std::array<int, 2>{std::min(f, g), std::max(f, g)}))
          return false;
    return true;
  };
  return self_pairs_closer_than(
      mesh, garment, gap,
      [&](const PointTriangleCandidate& c) {
        return tied({c.point}, {c.triangle[0], c.triangle[1], c.triangle[2]}) ||
               all_cross(holding({c.point}),
                         holding({c.triangle[0], c.triangle[1], c.triangle[2]}));
      },
      [&](const EdgeEdgeCandidate& c) {
        return tied({c.edge_a[0], c.edge_a[1]}, {c.edge_b[0], c.edge_b[1]}) ||
               all_cross(holding({c.edge_a[0], c.edge_a[1]}), holding({c.edge_b[0], c.edge_b[1]}));
      });
}

std::vector<std::array<int, 5>> tangled_pairs_closer_than(
    const ContactMesh& mesh, const Eigen::Ref<const MatrixX3d>& garment, double gap) {
  const std::vector<int>& tangles = mesh.garment_tangles;
  if (tangles.empty() || !mesh.self_contact) return {};
  const auto one_tangle = [&](std::initializer_list<int> vertices) {
    const int first = tangles[static_cast<std::size_t>(*vertices.begin())];
    if (first < 0) return false;
    for (const int v : vertices)
      if (tangles[static_cast<std::size_t>(v)] != first) return false;
    return true;
  };
  return self_pairs_closer_than(
      mesh, garment, gap,
      [&](const PointTriangleCandidate& c) {
        return one_tangle({c.point, c.triangle[0], c.triangle[1], c.triangle[2]});
      },
      [&](const EdgeEdgeCandidate& c) {
        return one_tangle({c.edge_a[0], c.edge_a[1], c.edge_b[0], c.edge_b[1]});
      });
}

}  // namespace gr
