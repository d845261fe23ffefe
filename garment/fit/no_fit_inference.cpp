#include "garment/fit/no_fit_inference.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/energies/fit_energy.hpp"
#include "core/mesh/boundary_loops.hpp"
#include "core/mesh/vertex_neighbours.hpp"
#include "core/skeleton/loop_bones.hpp"
#include "shrink/binding/voxel_binding.hpp"
#include "shrink/level_set/triangle_tree.hpp"

namespace gr {

namespace {

using Adjacency = std::vector<std::vector<int>>;

/// Connected regions of the vertices where `member` holds, over garment edges: a region id
/// per vertex (-1 outside) and the region count.
std::pair<std::vector<int>, int> regions(const Adjacency& neighbours,
                                         const std::vector<char>& member) {
  std::vector<int> region(member.size(), -1);
  int count = 0;
  for (std::size_t start = 0; start < member.size(); ++start) {
    if (!member[start] || region[start] >= 0) continue;
    std::vector<int> stack{static_cast<int>(start)};
    region[start] = count;
    while (!stack.empty()) {
      const int v = stack.back();
      stack.pop_back();
      for (int w : neighbours[static_cast<std::size_t>(v)])
        if (member[static_cast<std::size_t>(w)] && region[static_cast<std::size_t>(w)] < 0) {
          region[static_cast<std::size_t>(w)] = count;
          stack.push_back(w);
        }
    }
    ++count;
  }
  return {region, count};
}

/// Source body rule: loose vertices (beyond the snug offset by body_distance_edges mean edge
/// lengths) in regions that reach a boundary loop and are large enough, then the fitted
/// regions enclosed by them. Returns per vertex whether it is free; sets the snug offset.
std::vector<char> loose_from_body(const TriangleMesh& garment, const TriangleMesh& body,
                                  const Adjacency& neighbours, const NoFitOptions& options,
                                  double& snug_offset) {
  const auto n = static_cast<std::size_t>(garment.vertices.rows());
  const TriangleTree tree(body);
  std::vector<double> distance(n), edge(n, 0.0);
  for (std::size_t v = 0; v < n; ++v) {
    const Vector3d p = garment.vertices.row(static_cast<Eigen::Index>(v)).transpose();
    distance[v] = std::sqrt(tree.distance_sq(p));
    for (int w : neighbours[v])
      edge[v] += (garment.vertices.row(w).transpose() - p).norm() /
                 static_cast<double>(neighbours[v].size());
  }
  std::vector<double> sorted = distance;
  const auto rank = static_cast<std::size_t>(
      std::lround(options.snug_percentile / 100.0 * static_cast<double>(n - 1)));
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(rank),
                   sorted.end());
  snug_offset = sorted[rank];

  std::vector<char> boundary(n, 0);
  for (const auto& loop : boundary_loops(garment.faces))
    for (int v : loop) boundary[static_cast<std::size_t>(v)] = 1;
  std::vector<char> loose(n, 0);
  for (std::size_t v = 0; v < n; ++v)
    loose[v] = distance[v] - snug_offset > options.body_distance_edges * edge[v];

  const auto keep_regions = [&](const std::vector<char>& member, auto&& keep) {
    const auto [region, count] = regions(neighbours, member);
    std::vector<int> size(static_cast<std::size_t>(count), 0);
    std::vector<char> reaches_boundary(static_cast<std::size_t>(count), 0);
    for (std::size_t v = 0; v < n; ++v) {
      if (region[v] < 0) continue;
      ++size[static_cast<std::size_t>(region[v])];
      reaches_boundary[static_cast<std::size_t>(region[v])] |= boundary[v];
    }
    std::vector<char> kept(n, 0);
    for (std::size_t v = 0; v < n; ++v)
      if (region[v] >= 0)
        kept[v] = keep(size[static_cast<std::size_t>(region[v])],
                       reaches_boundary[static_cast<std::size_t>(region[v])] != 0);
    return kept;
  };
  const double min_size = options.min_region_share * static_cast<double>(n);
  std::vector<char> free =
      keep_regions(loose, [&](int size, bool reaches) { return reaches && size >= min_size; });
  std::vector<char> fitted(n);
  for (std::size_t v = 0; v < n; ++v) fitted[v] = !free[v];
  const std::vector<char> enclosed =
      keep_regions(fitted, [](int, bool reaches) { return !reaches; });
  for (std::size_t v = 0; v < n; ++v) free[v] |= enclosed[v];
  return free;
}

/// Skirt rule: below the plane across the legs hip_offset thigh lengths above the hips.
std::vector<char> below_hips(const TriangleMesh& garment, const Skeleton& skeleton,
                             const NoFitOptions& options) {
  const LegJoints legs = find_leg_joints(skeleton.bones, static_cast<int>(skeleton.joints.rows()),
                                         "the source skeleton");
  const auto joint = [&](int j) -> Vector3d { return skeleton.joints.row(j).transpose(); };
  const Vector3d hips = 0.5 * (joint(legs.hips[0]) + joint(legs.hips[1]));
  const Vector3d knees = 0.5 * (joint(legs.knees[0]) + joint(legs.knees[1]));
  const double thigh = (knees - hips).norm();
  std::vector<char> free(static_cast<std::size_t>(garment.vertices.rows()), 0);
  if (thigh == 0.0) return free;
  const Vector3d down = (knees - hips) / thigh;
  for (Eigen::Index v = 0; v < garment.vertices.rows(); ++v)
    free[static_cast<std::size_t>(v)] =
        (garment.vertices.row(v).transpose() - hips).dot(down) > -options.hip_offset * thigh;
  return free;
}

/// End joint rule: vertices nearest an end segment, the bone it continues or a bone leaving
/// the same joint as that bone, beyond the end joint less end_margin lengths of the bone.
std::vector<char> beyond_end_joints(const TriangleMesh& garment, const Skeleton& skeleton,
                                    const NoFitOptions& options) {
  BindingOptions segment_options;
  segment_options.root_joint = options.root_joint;
  segment_options.end_angle_degrees = options.end_angle_degrees;
  const std::vector<BoneSegment> segments = skeleton_segments(skeleton, segment_options);
  std::vector<char> free(static_cast<std::size_t>(garment.vertices.rows()), 0);
  for (Eigen::Index v = 0; v < garment.vertices.rows(); ++v) {
    const Vector3d p = garment.vertices.row(v).transpose();
    std::size_t nearest = 0;
    for (std::size_t s = 1; s < segments.size(); ++s)
      if (segments[s].distance(p) < segments[nearest].distance(p)) nearest = s;
    for (const BoneSegment& end : segments) {
      if (end.continues < 0) continue;
      const BoneSegment& bone = segments[static_cast<std::size_t>(end.continues)];
      const bool near = &segments[nearest] == &end ||
                        nearest == static_cast<std::size_t>(end.continues) ||
                        (segments[nearest].continues < 0 && segments[nearest].owner == bone.owner);
      const Vector3d along = bone.b - bone.a;
      const double length = along.norm();
      if (near && length > 0.0 && (p - bone.b).dot(along / length) > -options.end_margin * length)
        free[static_cast<std::size_t>(v)] = 1;
    }
  }
  return free;
}

int count_set(const std::vector<char>& flags) {
  return static_cast<int>(std::count(flags.begin(), flags.end(), 1));
}

}  // namespace

NoFitInference infer_no_fit(const TriangleMesh& garment, const TriangleMesh* source_body,
                            const Skeleton* source_skeleton,
                            const std::vector<char>& skirt_vertices, const NoFitOptions& options) {
  if (!(options.snug_percentile >= 0.0 && options.snug_percentile <= 100.0) ||
      !(options.body_distance_edges >= 0.0) || !(options.min_region_share >= 0.0) ||
      !std::isfinite(options.hip_offset) || !std::isfinite(options.end_margin))
    throw std::invalid_argument(
        "infer_no_fit: the percentile must be in [0, 100], edge counts and shares >= 0");
  if (source_skeleton &&
      (options.root_joint < 0 || options.root_joint >= source_skeleton->joints.rows()))
    throw std::invalid_argument("infer_no_fit: the root joint is out of range");
  NoFitInference inference;
  const auto n = static_cast<std::size_t>(garment.vertices.rows());
  std::vector<char> free(n, 0);
  std::vector<std::string> rules;
  const auto add = [&](const std::vector<char>& rule, int& count, const char* name) {
    count = count_set(rule);
    for (std::size_t v = 0; v < n; ++v) free[v] |= rule[v];
    rules.emplace_back(name);
  };
  if (source_body && source_body->faces.rows() > 0 && n > 0)
    add(loose_from_body(garment, *source_body, vertex_neighbours(garment), options,
                        inference.snug_offset),
        inference.from_body, "source body distance");
  if (source_skeleton &&
      std::find(skirt_vertices.begin(), skirt_vertices.end(), 1) != skirt_vertices.end()) {
    std::vector<char> rule = below_hips(garment, *source_skeleton, options);
    for (std::size_t v = 0; v < n; ++v) rule[v] = rule[v] && skirt_vertices[v];
    add(rule, inference.from_hips, "skirt below hips");
  }
  if (!source_body && source_skeleton && options.end_margin >= 0.0)
    add(beyond_end_joints(garment, *source_skeleton, options), inference.from_end_joints,
        "beyond end joints");
  for (std::size_t v = 0; v < n; ++v)
    if (free[v]) inference.vertices.push_back(static_cast<int>(v));
  inference.method = rules.empty() ? "none" : rules.front();
  for (std::size_t r = 1; r < rules.size(); ++r) inference.method += ", " + rules[r];
  return inference;
}

double no_fit_face_iou(const MatrixX3i& faces, int vertex_count, const std::vector<int>& a,
                       const std::vector<int>& b) {
  const std::vector<bool> fit_a = fit_face_mask(faces, vertex_count, a);
  const std::vector<bool> fit_b = fit_face_mask(faces, vertex_count, b);
  int both = 0, either = 0;
  for (std::size_t f = 0; f < fit_a.size(); ++f) {
    both += !fit_a[f] && !fit_b[f];
    either += !fit_a[f] || !fit_b[f];
  }
  return either == 0 ? 1.0 : static_cast<double>(both) / either;
}

}  // namespace gr
