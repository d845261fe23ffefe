#include "core/candidates/candidates.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "core/broad_phase/bvh.hpp"
#include "core/broad_phase/pair_separation.hpp"

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

/// How far (normalized units) a static query's vertex may lie off its segment of the last
/// swept motion and still count as on it: line-search points x + alpha dx differ from the
/// exact segment by rounding only, far below this.
constexpr double kOnMotionTolerance = 1e-10;

std::array<Vector3d, 4> gather(const Eigen::Ref<const MatrixX3d>& V, const std::array<int, 4>& ids) {
  return {V.row(ids[0]).transpose(), V.row(ids[1]).transpose(), V.row(ids[2]).transpose(),
          V.row(ids[3]).transpose()};
}

/// Whether the pair (vertices `ids`, split as in pair_separation_lower_bound) may come
/// within `threshold` somewhere along V0 → V1 (V0 and V1 the same matrix: at V0).
bool may_come_within(const Eigen::Ref<const MatrixX3d>& V0, const Eigen::Ref<const MatrixX3d>& V1,
                     const std::array<int, 4>& ids, int split, double threshold) {
  const std::array<Vector3d, 4> x0 = gather(V0, ids);
  const double bound = V0.data() == V1.data()
                           ? pair_separation_lower_bound(x0, split, threshold)
                           : pair_separation_lower_bound(x0, gather(V1, ids), split, threshold);
  return bound < threshold;
}

bool same_boxes(const std::vector<Box>& a, const std::vector<Box>& b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](const Box& x, const Box& y) {
           return x.min() == y.min() && x.max() == y.max();
         });
}

/// A tree refitted to each query's boxes, and rebuilt only when a refit has loosened it by
/// more than kMaxLoosening over its looseness when built.
struct RefittedTree {
  static constexpr double kMaxLoosening = 1.25;
  Bvh tree;
  double built_looseness = 0.0;
  void update(std::vector<Eigen::AlignedBox3d> boxes) {
    if (tree.size() == static_cast<int>(boxes.size()) && tree.size() > 0) {
      tree.refit(boxes);
      if (tree.looseness() <= kMaxLoosening * built_looseness) return;
    }
    tree.build(std::move(boxes));
    built_looseness = tree.looseness();
  }
};

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
      avatar_trees_(std::make_unique<AvatarTrees>()), garment_trees_(std::make_unique<GarmentTrees>()) {}

CandidateFinder::~CandidateFinder() = default;

void CandidateFinder::check_positions(const Eigen::Ref<const MatrixX3d>& V) const {
  if (V.rows() != mesh_.vertex_count())
    throw std::invalid_argument("contact positions have " + std::to_string(V.rows()) +
                                " rows, the contact mesh has " + std::to_string(mesh_.vertex_count()) +
                                " vertices");
}

Candidates CandidateFinder::box_pairs(const std::vector<Box>& vertex_boxes, double radius,
                                      const Eigen::Ref<const MatrixX3d>& V0,
                                      const Eigen::Ref<const MatrixX3d>& V1, double threshold) {
  const double grow = 0.5 * radius;
  const int ng = mesh_.garment_vertex_count;
  AvatarTrees& avatar = *avatar_trees_;
  std::vector<Box> avatar_vertex_boxes(vertex_boxes.begin() + ng, vertex_boxes.end());
  const bool rebuild_avatar = radius != avatar.radius || !same_boxes(avatar_vertex_boxes, avatar.vertex_boxes);
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
      [&] { if (rebuild_avatar) avatar.faces.build(element_boxes(mesh_.avatar_faces, vertex_boxes, grow)); },
      [&] { if (rebuild_avatar) avatar.edges.build(element_boxes(mesh_.avatar_edges, vertex_boxes, grow)); });

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
    return may_come_within(V0, V1, {v, t[0], t[1], t[2]}, 1, threshold);
  };
  const auto keep_ee = [&](const std::array<int, 2>& a, const std::array<int, 2>& b) {
    return may_come_within(V0, V1, {a[0], a[1], b[0], b[1]}, 2, threshold);
  };
  Candidates out;
  std::vector<PT> garment_avatar, self_pt, avatar_garment;
  std::vector<EE> edges_ga, self_ee;
  tbb::parallel_invoke(
      [&] {
        garment_avatar = garment_points.collect_pairs<PT>(avatar.faces, [&](int v, int f, std::vector<PT>& sink) {
          if (keep_pt(v, face(af, f))) sink.push_back({v, face(af, f)});
        });
      },
      [&] {
        avatar_garment = avatar.points.collect_pairs<PT>(garment_faces, [&](int i, int f, std::vector<PT>& sink) {
          const int v = avatar_points_[static_cast<std::size_t>(i)];
          if (keep_pt(v, face(gf, f))) sink.push_back({v, face(gf, f)});
        });
      },
      [&] {
        edges_ga = garment_edges.collect_pairs<EE>(avatar.edges, [&](int a, int b, std::vector<EE>& sink) {
          if (keep_ee(edge(ge, a), edge(ae, b))) sink.push_back({edge(ge, a), edge(ae, b)});
        });
      },
      [&] {
        if (self_contact)
          self_pairs(garment_point_boxes, garment_face_boxes, garment_edge_boxes, V0, V1, threshold,
                     self_pt, self_ee);
      });
  out.point_triangle = std::move(garment_avatar);
  out.point_triangle.insert(out.point_triangle.end(), self_pt.begin(), self_pt.end());
  out.point_triangle.insert(out.point_triangle.end(), avatar_garment.begin(), avatar_garment.end());
  out.edge_edge = std::move(edges_ga);
  out.edge_edge.insert(out.edge_edge.end(), self_ee.begin(), self_ee.end());
  return out;
}

/// The garment's regions with, per leaf, refitted trees over the points, faces and edges
/// it owns (group `leaves.size()` holds the points no face uses).
struct CandidateFinder::SelfSearch {
  GarmentRegions regions;
  std::vector<std::vector<int>> points, edges;  ///< per group, ids it owns
  std::vector<RefittedTree> point_trees, face_trees, edge_trees;
  std::vector<char> fold_free;   ///< per region, the last query's verdict
  std::vector<Box> extent;       ///< per region, the last query's box
  std::size_t fold_free_faces = 0;

  SelfSearch(const ContactMesh& mesh, const Eigen::Ref<const MatrixX3d>& garment)
      : regions(build_garment_regions(mesh.garment_faces, mesh.garment_edges, garment)) {
    const std::size_t groups = regions.leaves.size() + 1;
    points.assign(groups, {});
    edges.assign(groups, {});
    for (int v = 0; v < mesh.garment_vertex_count; ++v) {
      const int leaf = regions.vertex_leaf[static_cast<std::size_t>(v)];
      points[leaf >= 0 ? static_cast<std::size_t>(leaf) : groups - 1].push_back(v);
    }
    for (int e = 0; e < static_cast<int>(mesh.garment_edges.rows()); ++e)
      edges[static_cast<std::size_t>(regions.edge_leaf[static_cast<std::size_t>(e)])].push_back(e);
    point_trees.resize(groups);
    face_trees.resize(groups);
    edge_trees.resize(groups);
  }

  /// Marks fold-free regions top-down (a region found fold free is not split further).
  void mark_fold_free(int region, const MatrixX3i& faces, const Eigen::Ref<const MatrixX3d>& V0,
                      const Eigen::Ref<const MatrixX3d>& V1, double clearance) {
    const GarmentRegions::Region& r = regions.regions[static_cast<std::size_t>(region)];
    if (stays_fold_free(r, faces, V0, V1, clearance)) {
      fold_free[static_cast<std::size_t>(region)] = 1;
      return;
    }
    if (r.leaf >= 0) return;
    tbb::parallel_invoke([&] { mark_fold_free(r.children[0], faces, V0, V1, clearance); },
                         [&] { mark_fold_free(r.children[1], faces, V0, V1, clearance); });
  }

  /// Leaf pairs to search for pairs between regions a and b (boxes permitting).
  void cross(int a, int b, std::vector<std::pair<int, int>>& tasks) const {
    if (!extent[static_cast<std::size_t>(a)].intersects(extent[static_cast<std::size_t>(b)])) return;
    const GarmentRegions::Region& ra = regions.regions[static_cast<std::size_t>(a)];
    const GarmentRegions::Region& rb = regions.regions[static_cast<std::size_t>(b)];
    if (ra.leaf >= 0 && rb.leaf >= 0) {
      tasks.emplace_back(ra.leaf, rb.leaf);
    } else if (ra.leaf >= 0 || (rb.leaf < 0 && rb.faces.size() > ra.faces.size())) {
      cross(a, rb.children[0], tasks);
      cross(a, rb.children[1], tasks);
    } else {
      cross(ra.children[0], b, tasks);
      cross(ra.children[1], b, tasks);
    }
  }

  /// Leaf pairs to search within region r: none when it is fold free.
  void within(int r, std::vector<std::pair<int, int>>& tasks) const {
    if (fold_free[static_cast<std::size_t>(r)]) return;
    const GarmentRegions::Region& region = regions.regions[static_cast<std::size_t>(r)];
    if (region.leaf >= 0) {
      tasks.emplace_back(region.leaf, region.leaf);
      return;
    }
    within(region.children[0], tasks);
    within(region.children[1], tasks);
    cross(region.children[0], region.children[1], tasks);
  }
};

const GarmentRegions* CandidateFinder::regions() const { return self_ ? &self_->regions : nullptr; }

const std::vector<char>& CandidateFinder::fold_free() const {
  static const std::vector<char> none;
  return self_ ? self_->fold_free : none;
}

void CandidateFinder::self_pairs(const std::vector<Box>& point_boxes, const std::vector<Box>& face_boxes,
                                 const std::vector<Box>& edge_boxes, const Eigen::Ref<const MatrixX3d>& V0,
                                 const Eigen::Ref<const MatrixX3d>& V1, double threshold,
                                 std::vector<PointTriangleCandidate>& point_triangle,
                                 std::vector<EdgeEdgeCandidate>& edge_edge) {
  const auto& gf = mesh_.garment_faces;
  const auto& ge = mesh_.garment_edges;
  if (!self_) self_ = std::make_unique<SelfSearch>(mesh_, V0.topRows(mesh_.garment_vertex_count));
  SelfSearch& search = *self_;
  const GarmentRegions& regions = search.regions;
  const std::size_t leaf_count = regions.leaves.size();
  const std::size_t groups = leaf_count + 1;

  search.fold_free.assign(regions.regions.size(), 0);
  if (mesh_.cull_fold_free)
    tbb::parallel_for(std::size_t{0}, regions.roots.size(), [&](std::size_t k) {
      search.mark_fold_free(regions.roots[k], gf, V0, V1, threshold);
    });
  // Marked regions are maximal (the marking stops at them), hence disjoint.
  search.fold_free_faces = 0;
  for (std::size_t r = 0; r < regions.regions.size(); ++r)
    if (search.fold_free[r]) search.fold_free_faces += regions.regions[r].faces.size();

  // Refit each group's trees; region boxes bottom-up (children come first).
  const auto gather = [](const std::vector<Box>& boxes, const std::vector<int>& ids) {
    std::vector<Box> out(ids.size());
    for (std::size_t i = 0; i < ids.size(); ++i) out[i] = boxes[static_cast<std::size_t>(ids[i])];
    return out;
  };
  search.extent.assign(regions.regions.size(), Box());
  std::vector<Box> group_extent(groups);
  tbb::parallel_for(std::size_t{0}, groups, [&](std::size_t g) {
    Box& box = group_extent[g];
    std::vector<Box> boxes = gather(point_boxes, search.points[g]);
    for (const Box& b : boxes) box.extend(b);
    search.point_trees[g].update(std::move(boxes));
    if (g < leaf_count) {
      boxes = gather(face_boxes, regions.regions[static_cast<std::size_t>(regions.leaves[g])].faces);
      for (const Box& b : boxes) box.extend(b);
      search.face_trees[g].update(std::move(boxes));
    }
    boxes = gather(edge_boxes, search.edges[g]);
    for (const Box& b : boxes) box.extend(b);
    search.edge_trees[g].update(std::move(boxes));
  });
  for (std::size_t r = 0; r < regions.regions.size(); ++r) {
    const GarmentRegions::Region& region = regions.regions[r];
    search.extent[r] = region.leaf >= 0 ? group_extent[static_cast<std::size_t>(region.leaf)]
                                        : search.extent[static_cast<std::size_t>(region.children[0])].merged(
                                              search.extent[static_cast<std::size_t>(region.children[1])]);
  }
  const Box& loose = group_extent[leaf_count];

  std::vector<std::pair<int, int>> tasks;
  for (std::size_t i = 0; i < regions.roots.size(); ++i) {
    search.within(regions.roots[i], tasks);
    for (std::size_t j = i + 1; j < regions.roots.size(); ++j) search.cross(regions.roots[i], regions.roots[j], tasks);
  }
  if (mesh_.cull_fold_free) {
    // Two neighbouring leaves whose union stays fold free need no search between them.
    std::vector<const GarmentRegions::Region*> unions(tasks.size(), nullptr);
    for (std::size_t k = 0; k < tasks.size(); ++k) {
      const auto [a, b] = tasks[k];
      const auto it = regions.leaf_unions.find({std::min(a, b), std::max(a, b)});
      if (a != b && it != regions.leaf_unions.end()) unions[k] = &it->second;
    }
    std::vector<char> drop(tasks.size(), 0);
    tbb::parallel_for(std::size_t{0}, tasks.size(), [&](std::size_t k) {
      drop[k] = unions[k] && stays_fold_free(*unions[k], gf, V0, V1, threshold);
    });
    std::size_t kept = 0;
    for (std::size_t k = 0; k < tasks.size(); ++k)
      if (!drop[k]) tasks[kept++] = tasks[k];
    tasks.resize(kept);
  }
  if (!search.points[leaf_count].empty())
    for (std::size_t leaf = 0; leaf < leaf_count; ++leaf)
      if (loose.intersects(group_extent[leaf])) tasks.emplace_back(static_cast<int>(leaf_count), static_cast<int>(leaf));

  using PT = PointTriangleCandidate;
  using EE = EdgeEdgeCandidate;
  std::vector<std::vector<PT>> pt_sinks(tasks.size());
  std::vector<std::vector<EE>> ee_sinks(tasks.size());
  tbb::parallel_for(std::size_t{0}, tasks.size(), [&](std::size_t k) {
    const auto i = static_cast<std::size_t>(tasks[k].first), j = static_cast<std::size_t>(tasks[k].second);
    const auto point_face = [&](std::size_t point_group, std::size_t face_group) {
      if (face_group >= leaf_count) return;
      const std::vector<int>& point_ids = search.points[point_group];
      const std::vector<int>& face_ids = regions.regions[static_cast<std::size_t>(regions.leaves[face_group])].faces;
      search.point_trees[point_group].tree.append_pairs<PT>(
          search.face_trees[face_group].tree,
          [&](int a, int b, std::vector<PT>& sink) {
            const int v = point_ids[static_cast<std::size_t>(a)];
            const int f = face_ids[static_cast<std::size_t>(b)];
            if (gf(f, 0) != v && gf(f, 1) != v && gf(f, 2) != v &&
                may_come_within(V0, V1, {v, gf(f, 0), gf(f, 1), gf(f, 2)}, 1, threshold))
              sink.push_back({v, face(gf, f)});
          },
          pt_sinks[k]);
    };
    point_face(i, j);
    if (i != j) point_face(j, i);
    const std::vector<int>& edges_i = search.edges[i];
    const std::vector<int>& edges_j = search.edges[j];
    search.edge_trees[i].tree.append_pairs<EE>(
        search.edge_trees[j].tree,
        [&](int a, int b, std::vector<EE>& sink) {
          const int ea = edges_i[static_cast<std::size_t>(a)], eb = edges_j[static_cast<std::size_t>(b)];
          const int a0 = ge(ea, 0), a1 = ge(ea, 1), b0 = ge(eb, 0), b1 = ge(eb, 1);
          if (a0 != b0 && a0 != b1 && a1 != b0 && a1 != b1 &&
              may_come_within(V0, V1, {a0, a1, b0, b1}, 2, threshold))
            sink.push_back({{a0, a1}, {b0, b1}});
        },
        ee_sinks[k]);
  });
  for (auto& sink : pt_sinks) point_triangle.insert(point_triangle.end(), sink.begin(), sink.end());
  for (auto& sink : ee_sinks) edge_edge.insert(edge_edge.end(), sink.begin(), sink.end());
}

Candidates CandidateFinder::find(const Eigen::Ref<const MatrixX3d>& V, double inflation_radius) {
  check_positions(V);
  std::vector<Box> vertex_boxes(static_cast<std::size_t>(V.rows()));
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    const Vector3d p = V.row(i).transpose();
    vertex_boxes[static_cast<std::size_t>(i)] = Box(p, p);
  }
  if (inflation_radius <= swept_radius_ && on_swept_motion(V)) return filter_swept(V, inflation_radius);
  return box_pairs(vertex_boxes, inflation_radius, V, V, inflation_radius);
}

Candidates CandidateFinder::find_swept(const Eigen::Ref<const MatrixX3d>& V0,
                                       const Eigen::Ref<const MatrixX3d>& V1, double inflation_radius) {
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
  swept_ = box_pairs(vertex_boxes, inflation_radius, V0, V1, inflation_radius + 2.0 * kOnMotionTolerance);
  if (self_ && mesh_.garment_faces.rows() > 0) {
    ++swept_queries_;
    fold_free_fraction_sum_ +=
        static_cast<double>(self_->fold_free_faces) / static_cast<double>(mesh_.garment_faces.rows());
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

Candidates CandidateFinder::filter_swept(const Eigen::Ref<const MatrixX3d>& V, double radius) const {
  // Every pair that may be within the radius at V is in the swept list (V is on the swept
  // motion): keep those whose separation bound at V does not rule them out.
  const std::size_t npt = swept_.point_triangle.size();
  std::vector<char> keep(swept_.size(), 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, keep.size(), 1024), [&](const auto& range) {
    for (std::size_t k = range.begin(); k != range.end(); ++k) {
      if (k < npt) {
        const PointTriangleCandidate& c = swept_.point_triangle[k];
        keep[k] = may_come_within(V, V, {c.point, c.triangle[0], c.triangle[1], c.triangle[2]}, 1, radius);
      } else {
        const EdgeEdgeCandidate& c = swept_.edge_edge[k - npt];
        keep[k] = may_come_within(V, V, {c.edge_a[0], c.edge_a[1], c.edge_b[0], c.edge_b[1]}, 2, radius);
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
