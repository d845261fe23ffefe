#include "shrink/binding/voxel_binding.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <queue>
#include <stdexcept>
#include <utility>
#include <vector>

#include <tbb/parallel_for.h>

#include "core/common/stopwatch.hpp"
#include "shrink/binding/bone_heat.hpp"
#include "shrink/level_set/signed_distance_grid.hpp"

namespace gr {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
/// The narrow band the interior test needs: the sign is all that is read.
constexpr double kBandVoxels = 3.0;
/// A vertex attaches to interior voxels within this many voxels (per axis) of it; beyond,
/// it is bound through its mesh neighbours.
constexpr int kAttachReachVoxels = 2;

void check_inputs(const TriangleMesh& avatar, const Skeleton& skeleton,
                  const BindingOptions& options) {
  if (avatar.faces.rows() == 0 || avatar.vertices.rows() == 0)
    throw std::invalid_argument("bind_skeleton: the avatar has no face");
  if (avatar.faces.minCoeff() < 0 || avatar.faces.maxCoeff() >= avatar.vertices.rows())
    throw std::invalid_argument("bind_skeleton: an avatar face index is out of range");
  if (skeleton.bones.rows() == 0)
    throw std::invalid_argument("bind_skeleton: the skeleton has no bone");
  if (skeleton.bones.minCoeff() < 0 || skeleton.bones.maxCoeff() >= skeleton.joints.rows())
    throw std::invalid_argument("bind_skeleton: a bone index is out of range");
  if (options.root_joint < 0 || options.root_joint >= skeleton.joints.rows())
    throw std::invalid_argument("bind_skeleton: the root joint is out of range");
  if (options.resolution < 8 || !(options.falloff > 0.0) || !(options.distance_ratio >= 1.0) ||
      options.max_influences < 1 || !(options.end_length >= 0.0) ||
      !std::isfinite(options.falloff) || !std::isfinite(options.distance_ratio))
    throw std::invalid_argument(
        "bind_skeleton: resolution must be >= 8, falloff > 0, distance ratio >= 1, influences "
        ">= 1 and end length >= 0");
}

}  // namespace

Vector3d BoneSegment::closest_point(const Vector3d& p) const {
  const Vector3d ab = b - a;
  const double length_sq = ab.squaredNorm();
  const double s = length_sq > 0.0 ? std::clamp((p - a).dot(ab) / length_sq, 0.0, 1.0) : 0.0;
  return a + s * ab;
}

std::vector<BoneSegment> skeleton_segments(const Skeleton& skeleton,
                                           const BindingOptions& options) {
  const auto joint_count = static_cast<int>(skeleton.joints.rows());
  std::vector<std::vector<int>> neighbours(static_cast<std::size_t>(joint_count));
  for (Eigen::Index b = 0; b < skeleton.bones.rows(); ++b) {
    const int u = skeleton.bones(b, 0), v = skeleton.bones(b, 1);
    if (u == v) continue;
    neighbours[static_cast<std::size_t>(u)].push_back(v);
    neighbours[static_cast<std::size_t>(v)].push_back(u);
  }
  std::vector<int> parent(static_cast<std::size_t>(joint_count), -2);
  std::vector<int> order;
  for (int start = 0; start < joint_count; ++start) {
    const int root = start == 0 ? options.root_joint : start;
    if (parent[static_cast<std::size_t>(root)] != -2) continue;
    parent[static_cast<std::size_t>(root)] = -1;
    order.push_back(root);
    for (std::size_t head = order.size() - 1; head < order.size(); ++head)
      for (int next : neighbours[static_cast<std::size_t>(order[head])])
        if (parent[static_cast<std::size_t>(next)] == -2) {
          parent[static_cast<std::size_t>(next)] = order[head];
          order.push_back(next);
        }
  }
  const auto joint = [&](int j) -> Vector3d { return skeleton.joints.row(j).transpose(); };
  std::vector<BoneSegment> segments;
  std::vector<int> parent_bone(static_cast<std::size_t>(joint_count), -1);
  std::vector<Vector3d> child_directions(static_cast<std::size_t>(joint_count), Vector3d::Zero());
  std::vector<int> child_count(static_cast<std::size_t>(joint_count), 0);
  for (int j : order) {
    const int p = parent[static_cast<std::size_t>(j)];
    if (p < 0) continue;
    parent_bone[static_cast<std::size_t>(j)] = static_cast<int>(segments.size());
    segments.push_back({joint(p), joint(j), p});
    const Vector3d direction = joint(j) - joint(p);
    if (direction.norm() > 0.0)
      child_directions[static_cast<std::size_t>(p)] += direction.normalized();
    ++child_count[static_cast<std::size_t>(p)];
  }
  const double cos_end = std::cos(options.end_angle_degrees * M_PI / 180.0);
  for (int j : order) {
    const int p = parent[static_cast<std::size_t>(j)];
    if (p < 0 || options.end_length == 0.0) continue;
    const Vector3d bone = joint(j) - joint(p);
    if (bone.norm() == 0.0) continue;
    const Vector3d& children = child_directions[static_cast<std::size_t>(j)];
    const bool leaf = child_count[static_cast<std::size_t>(j)] == 0;
    const bool turns_away =
        !leaf && (children.norm() == 0.0 || children.normalized().dot(bone.normalized()) < cos_end);
    if (leaf || turns_away)
      segments.push_back({joint(j), joint(j) + options.end_length * bone, j,
                          parent_bone[static_cast<std::size_t>(j)]});
  }
  return segments;
}

namespace {

/// Passes on a grid build's stages as the one stage "binding grid".
class BindingGridStage final : public ForwardingInterrupter {
 public:
  using ForwardingInterrupter::ForwardingInterrupter;
  void start(const std::string&) override { next().start("binding grid"); }
};

/// The avatar's interior on a dense voxel box: voxel (i, j, k) of the box has its centre at
/// voxel_size * (origin + (i, j, k)).
class InteriorVoxels {
 public:
  InteriorVoxels(const TriangleMesh& avatar, double voxel_size, Interrupter& interrupter)
      : voxel_size_(voxel_size) {
    SignedDistanceOptions grid_options;
    grid_options.exterior_band = kBandVoxels * voxel_size;
    grid_options.full_depth = false;
    BindingGridStage grid_stage(interrupter);
    grid_options.interrupter = &grid_stage;
    const SignedDistanceGrid grid = build_signed_distance(avatar, voxel_size, grid_options);
    const Eigen::RowVector3d lo = avatar.vertices.colwise().minCoeff() / voxel_size;
    const Eigen::RowVector3d hi = avatar.vertices.colwise().maxCoeff() / voxel_size;
    for (int a = 0; a < 3; ++a) {
      origin_[a] = static_cast<int>(std::floor(lo[a])) - 1;
      size_[a] = static_cast<int>(std::ceil(hi[a])) + 1 - origin_[a] + 1;
    }
    const long long total = static_cast<long long>(size_[0]) * size_[1] * size_[2];
    index_.assign(static_cast<std::size_t>(total), -1);
    for (int i = 0; i < size_[0]; ++i)
      for (int j = 0; j < size_[1]; ++j)
        for (int k = 0; k < size_[2]; ++k) {
          const Eigen::Vector3i ijk(origin_[0] + i, origin_[1] + j, origin_[2] + k);
          if (grid.voxel_value(ijk) >= 0.0) continue;
          index_[static_cast<std::size_t>(flat(i, j, k))] = static_cast<int>(cells_.size());
          cells_.push_back({i, j, k});
        }
  }

  double voxel_size() const { return voxel_size_; }
  int count() const { return static_cast<int>(cells_.size()); }
  const std::array<int, 3>& cell(int n) const { return cells_[static_cast<std::size_t>(n)]; }
  /// Interior index of box voxel (i, j, k), -1 outside the interior or the box.
  int at(int i, int j, int k) const {
    if (i < 0 || j < 0 || k < 0 || i >= size_[0] || j >= size_[1] || k >= size_[2]) return -1;
    return index_[static_cast<std::size_t>(flat(i, j, k))];
  }
  Vector3d centre(int n) const {
    const auto& c = cell(n);
    return voxel_size_ * Vector3d(origin_[0] + c[0], origin_[1] + c[1], origin_[2] + c[2]);
  }
  /// Box coordinates of the voxel whose centre is nearest to p.
  std::array<int, 3> nearest_cell(const Vector3d& p) const {
    std::array<int, 3> c{};
    for (int a = 0; a < 3; ++a)
      c[a] =
          static_cast<int>(std::lround(p[a] / voxel_size_)) - origin_[static_cast<std::size_t>(a)];
    return c;
  }

 private:
  long long flat(int i, int j, int k) const {
    return (static_cast<long long>(i) * size_[1] + j) * size_[2] + k;
  }

  double voxel_size_;
  std::array<int, 3> origin_{};
  std::array<int, 3> size_{};
  std::vector<int> index_;
  std::vector<std::array<int, 3>> cells_;
};

/// Shortest-path distance from `segment` to every interior voxel, through interior voxels
/// (26-neighbourhood, steps of their centres' distance). Seeds: the interior voxels within
/// a voxel of the segment's nearest interior voxel distance, at their straight distance.
std::vector<double> interior_distances(const InteriorVoxels& voxels, const BoneSegment& segment) {
  const int n = voxels.count();
  const double h = voxels.voxel_size();
  std::vector<double> straight(static_cast<std::size_t>(n));
  double nearest = kInfinity;
  for (int v = 0; v < n; ++v) {
    straight[static_cast<std::size_t>(v)] = segment.distance(voxels.centre(v));
    nearest = std::min(nearest, straight[static_cast<std::size_t>(v)]);
  }
  std::vector<double> distance(static_cast<std::size_t>(n), kInfinity);
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  const double seed_radius = std::max(nearest, h) + 0.5 * h;
  for (int v = 0; v < n; ++v)
    if (straight[static_cast<std::size_t>(v)] <= seed_radius) {
      distance[static_cast<std::size_t>(v)] = straight[static_cast<std::size_t>(v)];
      queue.emplace(straight[static_cast<std::size_t>(v)], v);
    }
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > distance[static_cast<std::size_t>(v)]) continue;
    const auto& c = voxels.cell(v);
    for (int di = -1; di <= 1; ++di)
      for (int dj = -1; dj <= 1; ++dj)
        for (int dk = -1; dk <= 1; ++dk) {
          const int w = voxels.at(c[0] + di, c[1] + dj, c[2] + dk);
          if (w < 0 || w == v) continue;
          const double next = d + h * std::sqrt(static_cast<double>(di * di + dj * dj + dk * dk));
          if (next < distance[static_cast<std::size_t>(w)]) {
            distance[static_cast<std::size_t>(w)] = next;
            queue.emplace(next, w);
          }
        }
  }
  return distance;
}

/// The interior voxels a vertex attaches to: those within a voxel of its nearest interior
/// voxel (within kAttachReachVoxels per axis); empty when there is none.
std::vector<int> attached_voxels(const InteriorVoxels& voxels, const Vector3d& p) {
  const auto c = voxels.nearest_cell(p);
  std::vector<std::pair<double, int>> found;
  for (int di = -kAttachReachVoxels; di <= kAttachReachVoxels; ++di)
    for (int dj = -kAttachReachVoxels; dj <= kAttachReachVoxels; ++dj)
      for (int dk = -kAttachReachVoxels; dk <= kAttachReachVoxels; ++dk) {
        const int v = voxels.at(c[0] + di, c[1] + dj, c[2] + dk);
        if (v >= 0) found.emplace_back((voxels.centre(v) - p).norm(), v);
      }
  std::vector<int> attached;
  if (found.empty()) return attached;
  const double reach = std::min_element(found.begin(), found.end())->first + voxels.voxel_size();
  for (const auto& [d, v] : found)
    if (d <= reach) attached.push_back(v);
  return attached;
}

/// Whether the straight path from a surface point p to q stays inside: samples half a voxel
/// apart, skipping 1.5 voxels at each end (the surface point's own voxel, a bone touching
/// the surface).
bool sees_through_interior(const InteriorVoxels& voxels, const Vector3d& p, const Vector3d& q) {
  const double h = voxels.voxel_size();
  const double length = (q - p).norm();
  for (double s = 1.5 * h; s <= length - 1.5 * h; s += 0.5 * h) {
    const auto c = voxels.nearest_cell(p + (q - p) * (s / length));
    if (voxels.at(c[0], c[1], c[2]) < 0) return false;
  }
  return true;
}

/// Per vertex, its distance to every segment (#V×#S, infinity where unreachable), through
/// the interior: along shortest interior paths when `geodesic` (kGeodesic), else straight
/// to the segments it sees (kVisible, and kHeat's start). Rows of vertices with no interior
/// voxel near are all infinite.
Eigen::MatrixXd vertex_segment_distances(const TriangleMesh& avatar,
                                         const std::vector<BoneSegment>& segments,
                                         const InteriorVoxels& voxels, bool geodesic) {
  const Eigen::Index vertex_count = avatar.vertices.rows();
  const auto segment_count = static_cast<Eigen::Index>(segments.size());
  Eigen::MatrixXd distances = Eigen::MatrixXd::Constant(vertex_count, segment_count, kInfinity);
  std::vector<std::vector<int>> attached(static_cast<std::size_t>(vertex_count));
  tbb::parallel_for(Eigen::Index(0), vertex_count, [&](Eigen::Index v) {
    attached[static_cast<std::size_t>(v)] =
        attached_voxels(voxels, avatar.vertices.row(v).transpose());
  });
  if (geodesic) {
    std::vector<std::vector<double>> field(segments.size());
    tbb::parallel_for(std::size_t(0), segments.size(),
                      [&](std::size_t s) { field[s] = interior_distances(voxels, segments[s]); });
    tbb::parallel_for(Eigen::Index(0), vertex_count, [&](Eigen::Index v) {
      const Vector3d p = avatar.vertices.row(v).transpose();
      for (int w : attached[static_cast<std::size_t>(v)]) {
        const double step = (voxels.centre(w) - p).norm();
        for (Eigen::Index s = 0; s < segment_count; ++s)
          distances(v, s) =
              std::min(distances(v, s),
                       field[static_cast<std::size_t>(s)][static_cast<std::size_t>(w)] + step);
      }
    });
    return distances;
  }
  tbb::parallel_for(Eigen::Index(0), vertex_count, [&](Eigen::Index v) {
    if (attached[static_cast<std::size_t>(v)].empty()) return;
    const Vector3d p = avatar.vertices.row(v).transpose();
    for (Eigen::Index s = 0; s < segment_count; ++s) {
      const Vector3d q = segments[static_cast<std::size_t>(s)].closest_point(p);
      if (sees_through_interior(voxels, p, q)) distances(v, s) = (q - p).norm();
    }
  });
  return distances;
}

/// Gives every vertex whose row is all infinite the row of the nearest (along mesh edges)
/// vertex of its connected part that has a finite one; a part with none gets straight-line
/// distances. Counts the vertices bound each way.
void bind_unreached(const TriangleMesh& avatar, const std::vector<BoneSegment>& segments,
                    Eigen::MatrixXd& distances, Binding& binding) {
  const Eigen::Index vertex_count = avatar.vertices.rows();
  std::vector<std::vector<std::pair<int, double>>> edges(static_cast<std::size_t>(vertex_count));
  for (Eigen::Index f = 0; f < avatar.faces.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int a = avatar.faces(f, c), b = avatar.faces(f, (c + 1) % 3);
      const double length = (avatar.vertices.row(a) - avatar.vertices.row(b)).norm();
      edges[static_cast<std::size_t>(a)].emplace_back(b, length);
      edges[static_cast<std::size_t>(b)].emplace_back(a, length);
    }
  std::vector<double> path(static_cast<std::size_t>(vertex_count), kInfinity);
  std::vector<int> source(static_cast<std::size_t>(vertex_count), -1);
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  for (Eigen::Index v = 0; v < vertex_count; ++v)
    if (std::isfinite(distances.row(v).minCoeff())) {
      path[static_cast<std::size_t>(v)] = 0.0;
      source[static_cast<std::size_t>(v)] = static_cast<int>(v);
      queue.emplace(0.0, static_cast<int>(v));
    }
  binding.vertices_through_interior = static_cast<int>(queue.size());
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > path[static_cast<std::size_t>(v)]) continue;
    for (const auto& [w, length] : edges[static_cast<std::size_t>(v)])
      if (d + length < path[static_cast<std::size_t>(w)]) {
        path[static_cast<std::size_t>(w)] = d + length;
        source[static_cast<std::size_t>(w)] = source[static_cast<std::size_t>(v)];
        queue.emplace(d + length, w);
      }
  }
  for (Eigen::Index v = 0; v < vertex_count; ++v) {
    const int from = source[static_cast<std::size_t>(v)];
    if (from == v) continue;
    if (from >= 0) {
      distances.row(v) = distances.row(from);
      ++binding.vertices_through_neighbours;
      continue;
    }
    const Vector3d p = avatar.vertices.row(v).transpose();
    for (std::size_t s = 0; s < segments.size(); ++s)
      distances(v, static_cast<Eigen::Index>(s)) = segments[s].distance(p);
    ++binding.vertices_by_straight_line;
  }
}

/// Each vertex's largest-weight joint.
std::vector<int> dominant_joints(const Eigen::MatrixXd& weights) {
  std::vector<int> dominant(static_cast<std::size_t>(weights.cols()));
  for (Eigen::Index v = 0; v < weights.cols(); ++v) {
    Eigen::Index joint = 0;
    weights.col(v).maxCoeff(&joint);
    dominant[static_cast<std::size_t>(v)] = static_cast<int>(joint);
  }
  return dominant;
}

/// Vertices in islands: connected regions (over mesh edges) of one dominant joint all of
/// whose bordering vertices are dominated by joints that are neither theirs nor next to it
/// in the skeleton. Weights change along the skeleton across the surface, so such a region
/// was reached through a contact the interior voxels cannot tell apart (a hand resting on a
/// thigh, whose solids overlap).
std::vector<char> stray_islands(const TriangleMesh& avatar, const Eigen::MatrixXd& weights,
                                const Skeleton& skeleton) {
  const std::vector<int> dominant = dominant_joints(weights);
  const auto joint_count = static_cast<int>(skeleton.joints.rows());
  Eigen::MatrixXi adjacent = Eigen::MatrixXi::Identity(joint_count, joint_count);
  for (Eigen::Index b = 0; b < skeleton.bones.rows(); ++b) {
    adjacent(skeleton.bones(b, 0), skeleton.bones(b, 1)) = 1;
    adjacent(skeleton.bones(b, 1), skeleton.bones(b, 0)) = 1;
  }
  const std::size_t n = dominant.size();
  std::vector<std::vector<int>> neighbours(n);
  for (Eigen::Index f = 0; f < avatar.faces.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int a = avatar.faces(f, c), b = avatar.faces(f, (c + 1) % 3);
      neighbours[static_cast<std::size_t>(a)].push_back(b);
      neighbours[static_cast<std::size_t>(b)].push_back(a);
    }
  std::vector<char> island(n, 0);
  std::vector<int> region_of(n, -1);
  for (std::size_t start = 0; start < n; ++start) {
    if (region_of[start] >= 0) continue;
    const int joint = dominant[start];
    std::vector<int> members{static_cast<int>(start)};
    region_of[start] = static_cast<int>(start);
    bool borders = false, joined = false;
    for (std::size_t head = 0; head < members.size(); ++head)
      for (int w : neighbours[static_cast<std::size_t>(members[head])]) {
        const int other = dominant[static_cast<std::size_t>(w)];
        if (other != joint) {
          borders = true;
          joined |= adjacent(joint, other) != 0;
        } else if (region_of[static_cast<std::size_t>(w)] < 0) {
          region_of[static_cast<std::size_t>(w)] = static_cast<int>(start);
          members.push_back(w);
        }
      }
    if (borders && !joined)
      for (int v : members) island[static_cast<std::size_t>(v)] = 1;
  }
  return island;
}

/// Keeps a column's largest `max_influences` entries (ties: the lower joint) and normalizes
/// them to sum 1. @pre the column has a positive entry.
void keep_largest(Eigen::Ref<Eigen::VectorXd> column, int max_influences) {
  const auto joint_count = static_cast<int>(column.size());
  std::vector<int> order(static_cast<std::size_t>(joint_count));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return column[a] > column[b]; });
  for (int k = std::min(max_influences, joint_count); k < joint_count; ++k)
    column[order[static_cast<std::size_t>(k)]] = 0.0;
  column /= column.sum();
}

/// Weights from distances: the nearest segments within the ratio, d^-falloff (distances
/// plus a voxel, so a vertex on a bone is finite), summed per owner joint, the largest
/// max_influences joints kept and normalized.
Eigen::MatrixXd weights_from_distances(const Eigen::MatrixXd& distances,
                                       const std::vector<BoneSegment>& segments, int joint_count,
                                       double voxel_size, const BindingOptions& options) {
  const Eigen::Index vertex_count = distances.rows();
  Eigen::MatrixXd weights = Eigen::MatrixXd::Zero(joint_count, vertex_count);
  tbb::parallel_for(Eigen::Index(0), vertex_count, [&](Eigen::Index v) {
    const double nearest = distances.row(v).minCoeff() + voxel_size;
    for (std::size_t s = 0; s < segments.size(); ++s) {
      const double d = distances(v, static_cast<Eigen::Index>(s)) + voxel_size;
      if (d > options.distance_ratio * nearest) continue;
      weights(segments[s].owner, v) += std::pow(nearest / d, options.falloff);
    }
    keep_largest(weights.col(v), options.max_influences);
  });
  return weights;
}

/// kHeat's weights: bone heat from the visible distances; vertices left unheated (parts
/// where no vertex sees a bone) take the power falloff over `fallback` distances.
Eigen::MatrixXd heat_weights(const TriangleMesh& avatar, const std::vector<BoneSegment>& segments,
                             const Eigen::MatrixXd& visible, const Eigen::MatrixXd& fallback,
                             int joint_count, double voxel_size, const BindingOptions& options) {
  Eigen::MatrixXd weights = bone_heat(avatar, segments, visible, joint_count, voxel_size);
  const Eigen::MatrixXd falloff =
      weights_from_distances(fallback, segments, joint_count, voxel_size, options);
  for (Eigen::Index v = 0; v < weights.cols(); ++v) {
    if (weights.col(v).sum() > 0.0)
      keep_largest(weights.col(v), options.max_influences);
    else
      weights.col(v) = falloff.col(v);
  }
  return weights;
}

}  // namespace

const char* to_string(BindingMethod method) {
  switch (method) {
    case BindingMethod::kGeodesic: return "geodesic";
    case BindingMethod::kVisible: return "visible";
    case BindingMethod::kHeat: return "heat";
  }
  return "unknown";
}

Binding bind_skeleton(const TriangleMesh& avatar, const Skeleton& skeleton,
                      const BindingOptions& options) {
  check_inputs(avatar, skeleton, options);
  const Stopwatch stopwatch;
  Interrupter& interrupter = or_null(options.interrupter);
  interrupter.start("binding");
  interrupter.checkpoint(0.0);
  Binding binding;
  const std::vector<BoneSegment> segments = skeleton_segments(skeleton, options);
  binding.segments = static_cast<int>(segments.size());
  const double largest_side =
      (avatar.vertices.colwise().maxCoeff() - avatar.vertices.colwise().minCoeff()).maxCoeff();
  if (!(largest_side > 0.0) || !std::isfinite(largest_side))
    throw std::invalid_argument("bind_skeleton: the avatar has no extent");
  binding.voxel_size = largest_side / options.resolution;
  const InteriorVoxels voxels(avatar, binding.voxel_size, interrupter);
  binding.interior_voxels = voxels.count();
  interrupter.start("binding");
  interrupter.checkpoint(0.3);
  // A bool, not `heat ? kVisible : method`: GCC 12.2 -O2 then folds `heat` to false (phiopt).
  Eigen::MatrixXd distances = vertex_segment_distances(avatar, segments, voxels,
                                                       options.method == BindingMethod::kGeodesic);
  interrupter.checkpoint(0.9);
  const bool heat = options.method == BindingMethod::kHeat;
  const Eigen::MatrixXd visible = heat ? distances : Eigen::MatrixXd();
  bind_unreached(avatar, segments, distances, binding);
  const auto joint_count = static_cast<int>(skeleton.joints.rows());
  if (heat) {
    binding.weights = heat_weights(avatar, segments, visible, distances, joint_count,
                                   binding.voxel_size, options);
    binding.seconds = stopwatch.seconds();
    interrupter.checkpoint(1.0);
    return binding;
  }
  binding.weights =
      weights_from_distances(distances, segments, joint_count, binding.voxel_size, options);
  const std::vector<char> islands = stray_islands(avatar, binding.weights, skeleton);
  binding.vertices_rebound = static_cast<int>(std::count(islands.begin(), islands.end(), 1));
  if (binding.vertices_rebound > 0) {
    for (std::size_t v = 0; v < islands.size(); ++v)
      if (islands[v]) distances.row(static_cast<Eigen::Index>(v)).setConstant(kInfinity);
    Binding rebinding;
    bind_unreached(avatar, segments, distances, rebinding);
    binding.weights =
        weights_from_distances(distances, segments, joint_count, binding.voxel_size, options);
  }
  binding.seconds = stopwatch.seconds();
  interrupter.checkpoint(1.0);
  return binding;
}

WeightAgreement compare_skin_weights(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols())
    throw std::invalid_argument("compare_skin_weights: the weight matrices differ in shape");
  WeightAgreement agreement;
  double sum = 0.0;
  int same_dominant = 0;
  for (Eigen::Index v = 0; v < a.cols(); ++v) {
    const double total_a = a.col(v).sum(), total_b = b.col(v).sum();
    if (!(total_a > 0.0) || !(total_b > 0.0)) continue;
    ++agreement.vertices;
    sum += 1.0 - 0.5 * (a.col(v) / total_a - b.col(v) / total_b).cwiseAbs().sum();
    Eigen::Index dominant_a = 0, dominant_b = 0;
    a.col(v).maxCoeff(&dominant_a);
    b.col(v).maxCoeff(&dominant_b);
    if (dominant_a == dominant_b) ++same_dominant;
  }
  if (agreement.vertices > 0) {
    agreement.mean_agreement = sum / agreement.vertices;
    agreement.dominant_match = static_cast<double>(same_dominant) / agreement.vertices;
  }
  return agreement;
}

}  // namespace gr
