#include "core/candidates/fold_free_regions.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <deque>
#include <numeric>
#include <unordered_map>
#include <unordered_set>

namespace gr {
namespace {

std::uint64_t ordered_key(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}
std::uint64_t edge_key(int a, int b) { return a < b ? ordered_key(a, b) : ordered_key(b, a); }

struct FaceSide {
  int face;
  int from;  ///< the edge runs from → to in the face's orientation
};
using EdgeSides = std::unordered_map<std::uint64_t, std::vector<FaceSide>>;

/// Whether g joins f across the edge a → b of f: a manifold edge g runs the other way.
bool consistent_neighbour(const std::vector<FaceSide>& around, const FaceSide& side, int b) {
  return around.size() == 2 && side.from == b;
}

/// Fills vertices, and when the region is a disk, the boundary loop.
void finish_region(GarmentRegions::Region& region, const MatrixX3i& faces) {
  std::vector<std::uint64_t> directed, undirected;
  directed.reserve(3 * region.faces.size());
  undirected.reserve(3 * region.faces.size());
  std::vector<int> vertices;
  vertices.reserve(3 * region.faces.size());
  for (int f : region.faces)
    for (int k = 0; k < 3; ++k) {
      const int a = faces(f, k), b = faces(f, (k + 1) % 3);
      directed.push_back(ordered_key(a, b));
      undirected.push_back(edge_key(a, b));
      vertices.push_back(a);
    }
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  region.vertices = vertices;
  region.disk = false;
  region.boundary.clear();

  std::sort(directed.begin(), directed.end());
  std::sort(undirected.begin(), undirected.end());
  if (std::adjacent_find(directed.begin(), directed.end()) != directed.end())
    return;  // not oriented
  std::size_t edge_count = 0;
  for (std::size_t i = 0; i < undirected.size();) {
    std::size_t j = i;
    while (j < undirected.size() && undirected[j] == undirected[i]) ++j;
    if (j - i > 2) return;  // more than two faces on an edge
    ++edge_count;
    i = j;
  }
  const long euler = static_cast<long>(vertices.size()) - static_cast<long>(edge_count) +
                     static_cast<long>(region.faces.size());
  if (euler != 1) return;

  // Boundary edges: directed edges whose reverse is missing, as (from, to) sorted by from.
  std::vector<std::pair<int, int>> next;
  for (const std::uint64_t key : directed) {
    const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffffu);
    if (!std::binary_search(directed.begin(), directed.end(), ordered_key(b, a)))
      next.emplace_back(a, b);
  }
  if (next.size() < 3) return;
  for (std::size_t i = 1; i < next.size(); ++i)
    if (next[i].first == next[i - 1].first) return;  // two boundary edges leave a vertex: pinched
  const auto successor = [&](int v) {
    const auto it = std::lower_bound(next.begin(), next.end(), std::make_pair(v, INT32_MIN));
    return it != next.end() && it->first == v ? it->second : -1;
  };
  std::vector<int> loop;
  const int start = next.front().first;
  int v = start;
  do {
    loop.push_back(v);
    v = successor(v);
    if (v < 0 || loop.size() > next.size()) return;
  } while (v != start);
  if (loop.size() != next.size()) return;  // more than one boundary loop
  region.boundary = std::move(loop);
  region.disk = true;
}

Vector3d row(const Eigen::Ref<const MatrixX3d>& V, int i) { return V.row(i).transpose(); }

/// Leaves: compact patches of faces with similar normals (see build_garment_regions).
std::vector<std::vector<int>> grow_patches(const MatrixX3i& faces, const EdgeSides& sides,
                                           const Eigen::Ref<const MatrixX3d>& V, int max_faces,
                                           double max_normal_angle, std::vector<int>& face_patch) {
  const int face_count = static_cast<int>(faces.rows());
  std::vector<Vector3d> normals(static_cast<std::size_t>(face_count));
  std::vector<char> degenerate(static_cast<std::size_t>(face_count), 0);
  for (int f = 0; f < face_count; ++f) {
    const Vector3d n = (row(V, faces(f, 1)) - row(V, faces(f, 0)))
                           .cross(row(V, faces(f, 2)) - row(V, faces(f, 0)));
    const double length = n.norm();
    const auto i = static_cast<std::size_t>(f);
    degenerate[i] = !(length > 0.0) || !std::isfinite(length);
    normals[i] = degenerate[i] ? Vector3d::Zero() : Vector3d(n / length);
  }
  face_patch.assign(static_cast<std::size_t>(face_count), -1);
  const double min_cosine = std::cos(max_normal_angle);
  std::vector<std::vector<int>> patches;
  // Seeds come from the rim of the patches made so far, so patches stay compact.
  std::deque<int> seeds;
  int next_unassigned = 0;
  for (;;) {
    int seed = -1;
    while (!seeds.empty() && seed < 0) {
      if (face_patch[static_cast<std::size_t>(seeds.front())] < 0) seed = seeds.front();
      seeds.pop_front();
    }
    while (seed < 0 && next_unassigned < face_count) {
      if (face_patch[static_cast<std::size_t>(next_unassigned)] < 0) seed = next_unassigned;
      ++next_unassigned;
    }
    if (seed < 0) break;
    const int id = static_cast<int>(patches.size());
    std::vector<int> patch{seed};
    face_patch[static_cast<std::size_t>(seed)] = id;
    const Vector3d& seed_normal = normals[static_cast<std::size_t>(seed)];
    for (std::size_t head = 0; head < patch.size(); ++head) {
      const int f = patch[head];
      for (int k = 0; k < 3; ++k) {
        const int a = faces(f, k), b = faces(f, (k + 1) % 3);
        const std::vector<FaceSide>& around = sides.at(edge_key(a, b));
        for (const FaceSide& side : around) {
          const auto g = static_cast<std::size_t>(side.face);
          if (side.face == f || face_patch[g] >= 0) continue;
          const bool joinable = !degenerate[static_cast<std::size_t>(f)] && !degenerate[g] &&
                                consistent_neighbour(around, side, b) &&
                                normals[g].dot(seed_normal) >= min_cosine &&
                                static_cast<int>(patch.size()) < max_faces;
          if (joinable) {
            face_patch[g] = id;
            patch.push_back(side.face);
          } else {
            seeds.push_back(side.face);
          }
        }
      }
    }
    patches.push_back(std::move(patch));
  }
  return patches;
}

double cross2(const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
  return p.x() * q.y() - p.y() * q.x();
}

/// A quadratic in τ given by its Bernstein coefficients stays above `margin` on [0, 1].
bool stays_above(double b0, double b1, double b2, double margin) {
  return b0 > margin && b1 > margin && b2 > margin;
}

}  // namespace

GarmentRegions build_garment_regions(const MatrixX3i& faces, const MatrixX2i& edges,
                                     const Eigen::Ref<const MatrixX3d>& V, int max_leaf_faces,
                                     double max_normal_angle) {
  EdgeSides sides;
  sides.reserve(static_cast<std::size_t>(3 * faces.rows()));
  for (int f = 0; f < static_cast<int>(faces.rows()); ++f)
    for (int k = 0; k < 3; ++k)
      sides[edge_key(faces(f, k), faces(f, (k + 1) % 3))].push_back({f, faces(f, k)});

  GarmentRegions out;
  const std::vector<std::vector<int>> patches =
      grow_patches(faces, sides, V, max_leaf_faces, max_normal_angle, out.face_leaf);
  std::vector<int> level;
  for (std::size_t p = 0; p < patches.size(); ++p) {
    GarmentRegions::Region region;
    region.faces = patches[p];
    region.leaf = static_cast<int>(p);
    finish_region(region, faces);
    level.push_back(static_cast<int>(out.regions.size()));
    out.leaves.push_back(static_cast<int>(out.regions.size()));
    out.regions.push_back(std::move(region));
  }

  // Faces joined by a consistently oriented manifold edge, in a fixed order.
  std::vector<std::pair<int, int>> links;
  for (const auto& entry : sides) {
    const std::vector<FaceSide>& around = entry.second;
    if (around.size() == 2 && around[0].from != around[1].from)
      links.emplace_back(std::min(around[0].face, around[1].face),
                         std::max(around[0].face, around[1].face));
  }
  std::sort(links.begin(), links.end());
  for (const auto& [fa, fb] : links) {
    const int a = out.face_leaf[static_cast<std::size_t>(fa)];
    const int b = out.face_leaf[static_cast<std::size_t>(fb)];
    if (a == b) continue;
    const auto [it, added] = out.leaf_unions.try_emplace({std::min(a, b), std::max(a, b)});
    if (!added) continue;
    GarmentRegions::Region& joined = it->second;
    joined.faces = patches[static_cast<std::size_t>(std::min(a, b))];
    const std::vector<int>& more = patches[static_cast<std::size_t>(std::max(a, b))];
    joined.faces.insert(joined.faces.end(), more.begin(), more.end());
    finish_region(joined, faces);
  }

  // Join regions pairwise, level by level, along the consistently oriented edges they share.
  std::vector<int> face_region(static_cast<std::size_t>(faces.rows()));
  for (;;) {
    for (int r : level)
      for (int f : out.regions[static_cast<std::size_t>(r)].faces)
        face_region[static_cast<std::size_t>(f)] = r;
    std::vector<std::pair<int, int>> seams;  // region pairs, once per shared edge
    for (const auto& [fa, fb] : links) {
      const int a = face_region[static_cast<std::size_t>(fa)],
                b = face_region[static_cast<std::size_t>(fb)];
      if (a != b) seams.emplace_back(std::min(a, b), std::max(a, b));
    }
    std::sort(seams.begin(), seams.end());
    std::unordered_map<int, std::vector<std::pair<int, int>>>
        neighbours;  // region → (shared edges, other)
    for (std::size_t i = 0; i < seams.size();) {
      std::size_t j = i;
      while (j < seams.size() && seams[j] == seams[i]) ++j;
      const int count = static_cast<int>(j - i);
      neighbours[seams[i].first].emplace_back(count, seams[i].second);
      neighbours[seams[i].second].emplace_back(count, seams[i].first);
      i = j;
    }
    std::unordered_set<int> joined;
    std::vector<int> next_level;
    bool any = false;
    // Smallest regions first, each with its smallest free neighbour (then the one it shares
    // the most edges with): sizes stay balanced, so the hierarchy stays shallow.
    const auto size_of = [&](int r) {
      return out.regions[static_cast<std::size_t>(r)].faces.size();
    };
    std::vector<int> order = level;
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return size_of(a) < size_of(b); });
    for (int r : order) {
      if (joined.count(r)) continue;
      int best = -1, best_count = 0;
      for (const auto& [count, other] : neighbours[r]) {
        if (joined.count(other)) continue;
        const bool better = best < 0 || size_of(other) < size_of(best) ||
                            (size_of(other) == size_of(best) &&
                             (count > best_count || (count == best_count && other < best)));
        if (better) {
          best = other;
          best_count = count;
        }
      }
      if (best < 0) continue;
      joined.insert(r);
      joined.insert(best);
      GarmentRegions::Region region;
      region.children = {r, best};
      region.faces = out.regions[static_cast<std::size_t>(r)].faces;
      const std::vector<int>& more = out.regions[static_cast<std::size_t>(best)].faces;
      region.faces.insert(region.faces.end(), more.begin(), more.end());
      finish_region(region, faces);
      next_level.push_back(static_cast<int>(out.regions.size()));
      out.regions.push_back(std::move(region));
      any = true;
    }
    for (int r : level)
      if (!joined.count(r)) next_level.push_back(r);
    level.swap(next_level);
    if (!any) break;
  }
  out.roots = level;

  out.vertex_leaf.assign(static_cast<std::size_t>(V.rows()), -1);
  for (std::size_t p = 0; p < out.leaves.size(); ++p)
    for (int v : out.regions[static_cast<std::size_t>(out.leaves[p])].vertices)
      if (out.vertex_leaf[static_cast<std::size_t>(v)] < 0)
        out.vertex_leaf[static_cast<std::size_t>(v)] = static_cast<int>(p);
  out.edge_leaf.assign(static_cast<std::size_t>(edges.rows()), -1);
  for (Eigen::Index e = 0; e < edges.rows(); ++e) {
    const auto it = sides.find(edge_key(edges(e, 0), edges(e, 1)));
    if (it != sides.end() && !it->second.empty())
      out.edge_leaf[static_cast<std::size_t>(e)] =
          out.face_leaf[static_cast<std::size_t>(it->second.front().face)];
  }
  return out;
}

bool stays_fold_free(const GarmentRegions::Region& region, const MatrixX3i& faces,
                     const Eigen::Ref<const MatrixX3d>& V0, const Eigen::Ref<const MatrixX3d>& V1,
                     double clearance) {
  if (!region.disk) return false;
  Vector3d axis = Vector3d::Zero();
  for (int f : region.faces) {
    const Vector3d p0 = row(V0, faces(f, 0));
    axis += (row(V0, faces(f, 1)) - p0).cross(row(V0, faces(f, 2)) - p0);
  }
  Vector3d c0 = Vector3d::Zero(), c1 = Vector3d::Zero();
  Eigen::AlignedBox3d extent;
  for (int v : region.vertices) {
    c0 += row(V0, v);
    c1 += row(V1, v);
    extent.extend(row(V0, v));
    extent.extend(row(V1, v));
  }
  const double axis_length = axis.norm();
  const double size = extent.diagonal().norm();
  if (!(axis_length > 0.0) || !std::isfinite(axis_length) || !std::isfinite(size)) return false;
  const Vector3d a = axis / axis_length;
  c0 /= static_cast<double>(region.vertices.size());
  c1 /= static_cast<double>(region.vertices.size());

  // A sign is trusted only above a margin that rounding cannot reach: relative to the
  // lengths involved, with an absolute floor for tiny ones.
  constexpr double kRelativeMargin = 1e-9;
  const double floor = 1e-12 * size * size;

  for (int f : region.faces) {
    const Vector3d p0 = row(V0, faces(f, 0)), q0 = row(V1, faces(f, 0));
    const Vector3d e1 = row(V0, faces(f, 1)) - p0, e2 = row(V0, faces(f, 2)) - p0;
    const Vector3d f1 = row(V1, faces(f, 1)) - q0, f2 = row(V1, faces(f, 2)) - q0;
    const double scale = (e1.norm() + f1.norm()) * (e2.norm() + f2.norm());
    // Twice the projected area over the longest edge bounds the projected heights: keep
    // them above the clearance (edge lengths along the motion are at most their largest
    // end value).
    const double longest =
        std::max({e1.norm(), e2.norm(), (e2 - e1).norm(), f1.norm(), f2.norm(), (f2 - f1).norm()});
    if (!stays_above(a.dot(e1.cross(e2)), 0.5 * a.dot(e1.cross(f2) + f1.cross(e2)),
                     a.dot(f1.cross(f2)), clearance * longest + kRelativeMargin * scale + floor))
      return false;
  }

  // The boundary in the plane, relative to the centroid: each point moves linearly in τ.
  const Vector3d u = a.unitOrthogonal();
  const Vector3d w = a.cross(u);
  const std::size_t n = region.boundary.size();
  std::vector<Eigen::Vector2d> start(n), end(n);
  for (std::size_t k = 0; k < n; ++k) {
    const Vector3d p = row(V0, region.boundary[k]) - c0, q = row(V1, region.boundary[k]) - c1;
    start[k] = {p.dot(u), p.dot(w)};
    end[k] = {q.dot(u), q.dot(w)};
  }
  // Consecutive edges p → q → r: the directions q→p and q→r never coincide.
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t q = (k + 1) % n, r = (k + 2) % n;
    const Eigen::Vector2d d0 = start[k] - start[q], d1 = end[k] - end[q];
    const Eigen::Vector2d g0 = start[r] - start[q], g1 = end[r] - end[q];
    const double margin =
        kRelativeMargin * (d0.norm() + d1.norm()) * (g0.norm() + g1.norm()) + floor;
    const double c0b = cross2(d0, g0), c1b = 0.5 * (cross2(d0, g1) + cross2(d1, g0)),
                 c2b = cross2(d1, g1);
    const double s0 = d0.dot(g0), s1 = 0.5 * (d0.dot(g1) + d1.dot(g0)), s2 = d1.dot(g1);
    if (!stays_above(c0b, c1b, c2b, margin) && !stays_above(-c0b, -c1b, -c2b, margin) &&
        !stays_above(-s0, -s1, -s2, margin))
      return false;
  }
  // Any two other edges: their swept hulls (in relative coordinates) have a separating axis.
  struct Hull {
    std::array<Eigen::Vector2d, 4> points;
    Eigen::AlignedBox2d box;
  };
  std::vector<Hull> hulls(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t next = (k + 1) % n;
    hulls[k].points = {start[k], start[next], end[k], end[next]};
    for (const auto& p : hulls[k].points) hulls[k].box.extend(p);
  }
  const double gap = clearance + kRelativeMargin * size + 1e-12 * size;
  const auto separated = [&](const Hull& A, const Hull& B) {
    const auto split_by = [&](const Eigen::Vector2d& axis_2d) {
      double a_min = INFINITY, a_max = -INFINITY, b_min = INFINITY, b_max = -INFINITY;
      for (const auto& p : A.points) {
        a_min = std::min(a_min, p.dot(axis_2d));
        a_max = std::max(a_max, p.dot(axis_2d));
      }
      for (const auto& p : B.points) {
        b_min = std::min(b_min, p.dot(axis_2d));
        b_max = std::max(b_max, p.dot(axis_2d));
      }
      return a_max + gap < b_min || b_max + gap < a_min;
    };
    for (const Hull* H : {&A, &B})
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) {
          const Eigen::Vector2d d =
              H->points[static_cast<std::size_t>(j)] - H->points[static_cast<std::size_t>(i)];
          const double length = d.norm();
          if (!(length > 0.0)) continue;
          const Eigen::Vector2d along = d / length;
          if (split_by(along) || split_by(Eigen::Vector2d(-along.y(), along.x()))) return true;
        }
    return false;
  };
  // Sweep over the hulls' boxes along x: only overlapping boxes need the axis test.
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) {
    return hulls[i].box.min().x() < hulls[j].box.min().x() ||
           (hulls[i].box.min().x() == hulls[j].box.min().x() && i < j);
  });
  for (std::size_t x = 0; x < n; ++x) {
    const Hull& A = hulls[order[x]];
    for (std::size_t y = x + 1; y < n && hulls[order[y]].box.min().x() <= A.box.max().x() + gap;
         ++y) {
      const std::size_t i = order[x], j = order[y];
      const std::size_t apart = i > j ? i - j : j - i;
      if (apart == 1 || apart == n - 1) continue;  // consecutive: handled above
      const Hull& B = hulls[j];
      if (A.box.min().y() > B.box.max().y() + gap || B.box.min().y() > A.box.max().y() + gap)
        continue;
      if (!separated(A, B)) return false;
    }
  }
  return true;
}

}  // namespace gr
