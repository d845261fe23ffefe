#include "core/candidates/self_contact_search.hpp"

#include <algorithm>
#include <array>
#include <utility>

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "core/broad_phase/pair_separation.hpp"

namespace gr {
namespace {

std::array<int, 3> face(const MatrixX3i& faces, int f) {
  return {faces(f, 0), faces(f, 1), faces(f, 2)};
}

}  // namespace

SelfContactSearch::SelfContactSearch(const ContactMesh& mesh,
                                     const Eigen::Ref<const MatrixX3d>& garment)
    : mesh_(mesh),
      regions_(build_garment_regions(mesh.garment_faces, mesh.garment_edges, garment)) {
  const std::size_t groups = regions_.leaves.size() + 1;
  points_.assign(groups, {});
  edges_.assign(groups, {});
  for (int v = 0; v < mesh.garment_vertex_count; ++v) {
    const int leaf = regions_.vertex_leaf[static_cast<std::size_t>(v)];
    points_[leaf >= 0 ? static_cast<std::size_t>(leaf) : groups - 1].push_back(v);
  }
  for (int e = 0; e < static_cast<int>(mesh.garment_edges.rows()); ++e)
    edges_[static_cast<std::size_t>(regions_.edge_leaf[static_cast<std::size_t>(e)])].push_back(e);
  point_trees_.resize(groups);
  face_trees_.resize(groups);
  edge_trees_.resize(groups);
}

void SelfContactSearch::mark_fold_free(int region, const Eigen::Ref<const MatrixX3d>& V0,
                                       const Eigen::Ref<const MatrixX3d>& V1, double clearance) {
  const GarmentRegions::Region& r = regions_.regions[static_cast<std::size_t>(region)];
  if (stays_fold_free(r, mesh_.garment_faces, V0, V1, clearance)) {
    fold_free_[static_cast<std::size_t>(region)] = 1;
    return;
  }
  if (r.leaf >= 0) return;
  tbb::parallel_invoke([&] { mark_fold_free(r.children[0], V0, V1, clearance); },
                       [&] { mark_fold_free(r.children[1], V0, V1, clearance); });
}

void SelfContactSearch::cross(int a, int b, std::vector<std::pair<int, int>>& tasks) const {
  if (!extent_[static_cast<std::size_t>(a)].intersects(extent_[static_cast<std::size_t>(b)]))
    return;
  const GarmentRegions::Region& ra = regions_.regions[static_cast<std::size_t>(a)];
  const GarmentRegions::Region& rb = regions_.regions[static_cast<std::size_t>(b)];
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

void SelfContactSearch::within(int r, std::vector<std::pair<int, int>>& tasks) const {
  if (fold_free_[static_cast<std::size_t>(r)]) return;
  const GarmentRegions::Region& region = regions_.regions[static_cast<std::size_t>(r)];
  if (region.leaf >= 0) {
    tasks.emplace_back(region.leaf, region.leaf);
    return;
  }
  within(region.children[0], tasks);
  within(region.children[1], tasks);
  cross(region.children[0], region.children[1], tasks);
}

void SelfContactSearch::find(const std::vector<Box>& point_boxes,
                             const std::vector<Box>& face_boxes, const std::vector<Box>& edge_boxes,
                             const Eigen::Ref<const MatrixX3d>& V0,
                             const Eigen::Ref<const MatrixX3d>& V1, double threshold,
                             std::vector<PointTriangleCandidate>& point_triangle,
                             std::vector<EdgeEdgeCandidate>& edge_edge) {
  const auto& gf = mesh_.garment_faces;
  const auto& ge = mesh_.garment_edges;
  const GarmentRegions& regions = regions_;
  const std::size_t leaf_count = regions.leaves.size();
  const std::size_t groups = leaf_count + 1;

  fold_free_.assign(regions.regions.size(), 0);
  if (mesh_.cull_fold_free)
    tbb::parallel_for(std::size_t{0}, regions.roots.size(),
                      [&](std::size_t k) { mark_fold_free(regions.roots[k], V0, V1, threshold); });
  // Marked regions are maximal (the marking stops at them), hence disjoint.
  fold_free_faces_ = 0;
  for (std::size_t r = 0; r < regions.regions.size(); ++r)
    if (fold_free_[r]) fold_free_faces_ += regions.regions[r].faces.size();

  // Refit each group's trees; region boxes bottom-up (children come first).
  const auto gather = [](const std::vector<Box>& boxes, const std::vector<int>& ids) {
    std::vector<Box> out(ids.size());
    for (std::size_t i = 0; i < ids.size(); ++i) out[i] = boxes[static_cast<std::size_t>(ids[i])];
    return out;
  };
  extent_.assign(regions.regions.size(), Box());
  std::vector<Box> group_extent(groups);
  tbb::parallel_for(std::size_t{0}, groups, [&](std::size_t g) {
    Box& box = group_extent[g];
    std::vector<Box> boxes = gather(point_boxes, points_[g]);
    for (const Box& b : boxes) box.extend(b);
    point_trees_[g].update(std::move(boxes));
    if (g < leaf_count) {
      boxes =
          gather(face_boxes, regions.regions[static_cast<std::size_t>(regions.leaves[g])].faces);
      for (const Box& b : boxes) box.extend(b);
      face_trees_[g].update(std::move(boxes));
    }
    boxes = gather(edge_boxes, edges_[g]);
    for (const Box& b : boxes) box.extend(b);
    edge_trees_[g].update(std::move(boxes));
  });
  for (std::size_t r = 0; r < regions.regions.size(); ++r) {
    const GarmentRegions::Region& region = regions.regions[r];
    extent_[r] = region.leaf >= 0 ? group_extent[static_cast<std::size_t>(region.leaf)]
                                  : extent_[static_cast<std::size_t>(region.children[0])].merged(
                                        extent_[static_cast<std::size_t>(region.children[1])]);
  }
  const Box& loose = group_extent[leaf_count];

  std::vector<std::pair<int, int>> tasks;
  for (std::size_t i = 0; i < regions.roots.size(); ++i) {
    within(regions.roots[i], tasks);
    for (std::size_t j = i + 1; j < regions.roots.size(); ++j)
      cross(regions.roots[i], regions.roots[j], tasks);
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
  if (!points_[leaf_count].empty())
    for (std::size_t leaf = 0; leaf < leaf_count; ++leaf)
      if (loose.intersects(group_extent[leaf]))
        tasks.emplace_back(static_cast<int>(leaf_count), static_cast<int>(leaf));

  using PT = PointTriangleCandidate;
  using EE = EdgeEdgeCandidate;
  std::vector<std::vector<PT>> pt_sinks(tasks.size());
  std::vector<std::vector<EE>> ee_sinks(tasks.size());
  tbb::parallel_for(std::size_t{0}, tasks.size(), [&](std::size_t k) {
    const auto i = static_cast<std::size_t>(tasks[k].first),
               j = static_cast<std::size_t>(tasks[k].second);
    const auto point_face = [&](std::size_t point_group, std::size_t face_group) {
      if (face_group >= leaf_count) return;
      const std::vector<int>& point_ids = points_[point_group];
      const std::vector<int>& face_ids =
          regions.regions[static_cast<std::size_t>(regions.leaves[face_group])].faces;
      point_trees_[point_group].tree.append_pairs<PT>(
          face_trees_[face_group].tree,
          [&](int a, int b, std::vector<PT>& sink) {
            const int v = point_ids[static_cast<std::size_t>(a)];
            const int f = face_ids[static_cast<std::size_t>(b)];
            if (gf(f, 0) != v && gf(f, 1) != v && gf(f, 2) != v &&
                pair_may_come_within(V0, V1, {v, gf(f, 0), gf(f, 1), gf(f, 2)}, 1, threshold))
              sink.push_back({v, face(gf, f)});
          },
          pt_sinks[k]);
    };
    point_face(i, j);
    if (i != j) point_face(j, i);
    const std::vector<int>& edges_i = edges_[i];
    const std::vector<int>& edges_j = edges_[j];
    edge_trees_[i].tree.append_pairs<EE>(
        edge_trees_[j].tree,
        [&](int a, int b, std::vector<EE>& sink) {
          const int ea = edges_i[static_cast<std::size_t>(a)],
                    eb = edges_j[static_cast<std::size_t>(b)];
          const int a0 = ge(ea, 0), a1 = ge(ea, 1), b0 = ge(eb, 0), b1 = ge(eb, 1);
          if (a0 != b0 && a0 != b1 && a1 != b0 && a1 != b1 &&
              pair_may_come_within(V0, V1, {a0, a1, b0, b1}, 2, threshold))
            sink.push_back({{a0, a1}, {b0, b1}});
        },
        ee_sinks[k]);
  });
  for (auto& sink : pt_sinks) point_triangle.insert(point_triangle.end(), sink.begin(), sink.end());
  for (auto& sink : ee_sinks) edge_edge.insert(edge_edge.end(), sink.begin(), sink.end());
}

}  // namespace gr
