#include "garment/layers/hidden_faces.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include <CGAL/AABB_segment_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <tbb/parallel_for.h>

#include "garment/layers/surface_rays.hpp"

namespace gr {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Segment = Kernel::Segment_3;
using SegmentPrimitive = CGAL::AABB_segment_primitive<Kernel, std::vector<Segment>::const_iterator>;
using SegmentTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, SegmentPrimitive>>;

/// The edges of `faces` that belong to exactly one face, smaller vertex first, sorted.
std::vector<std::pair<int, int>> open_edges(const MatrixX3i& faces) {
  std::vector<std::pair<int, int>> edges;
  edges.reserve(static_cast<std::size_t>(faces.rows()) * 3);
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = faces(f, k), b = faces(f, (k + 1) % 3);
      if (a != b) edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  std::sort(edges.begin(), edges.end());
  std::vector<std::pair<int, int>> out;
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if (j - i == 1) out.push_back(edges[i]);
    i = j;
  }
  return out;
}

enum class FaceFate : char { kHidden, kEscaping, kNearOpening, kDegenerate };
}  // namespace

HiddenFaces faces_hidden_by_outfit(const TriangleMesh& avatar, const TriangleMesh& outfit,
                                   const HiddenFaceOptions& options) {
  if (!(options.margin >= 0.0))
    throw std::invalid_argument("faces_hidden_by_outfit: the margin must be non-negative");
  if (!(options.cone_half_angle_degrees >= 0.0 && options.cone_half_angle_degrees < 90.0))
    throw std::invalid_argument("faces_hidden_by_outfit: the cone half-angle must be in [0, 90)");
  if (options.ring_rays < 0)
    throw std::invalid_argument("faces_hidden_by_outfit: ring_rays must be non-negative");

  const SurfaceRays garments(outfit);
  std::vector<Segment> openings;
  const auto point = [&](int v) {
    return Kernel::Point_3(outfit.vertices(v, 0), outfit.vertices(v, 1), outfit.vertices(v, 2));
  };
  for (const auto& [a, b] : open_edges(outfit.faces)) {
    Segment s(point(a), point(b));
    if (!s.is_degenerate()) openings.push_back(s);
  }
  SegmentTree opening_tree(openings.cbegin(), openings.cend());
  if (!openings.empty()) {
    opening_tree.accelerate_distance_queries();
    // CGAL builds its search structures lazily: one serial query before the parallel ones.
    opening_tree.squared_distance(openings.front().source());
  }
  const double margin_sq = options.margin * options.margin;
  const auto near_opening = [&](const Vector3d& p) {
    return !openings.empty() &&
           opening_tree.squared_distance(Kernel::Point_3(p.x(), p.y(), p.z())) <= margin_sq;
  };

  const FaceFrames frames = face_frames(avatar);
  const double alpha = options.cone_half_angle_degrees * M_PI / 180.0;
  const Eigen::Index count = avatar.faces.rows();
  std::vector<FaceFate> fate(static_cast<std::size_t>(count), FaceFate::kEscaping);
  tbb::parallel_for(Eigen::Index(0), count, [&](Eigen::Index f) {
    FaceFate& out = fate[static_cast<std::size_t>(f)];
    const Vector3d n = frames.normals.row(f).transpose();
    if (n.isZero()) {
      out = FaceFate::kDegenerate;
      return;
    }
    const Vector3d centroid = frames.centroids.row(f).transpose();
    if (!garments.meets(centroid, n)) return;
    const Vector3d u = unit_perpendicular(n), v = n.cross(u);
    for (int k = 0; k < options.ring_rays; ++k) {
      const double theta = 2.0 * M_PI * k / options.ring_rays;
      const Vector3d d =
          std::cos(alpha) * n + std::sin(alpha) * (std::cos(theta) * u + std::sin(theta) * v);
      if (!garments.meets(centroid, d)) return;
    }
    bool near = near_opening(centroid);
    for (int k = 0; k < 3 && !near; ++k)
      near = near_opening(avatar.vertices.row(avatar.faces(f, k)).transpose());
    out = near ? FaceFate::kNearOpening : FaceFate::kHidden;
  });

  HiddenFaces out;
  out.face_count = static_cast<int>(count);
  for (Eigen::Index f = 0; f < count; ++f) switch (fate[static_cast<std::size_t>(f)]) {
      case FaceFate::kHidden: out.faces.push_back(static_cast<int>(f)); break;
      case FaceFate::kEscaping: ++out.kept_escaping; break;
      case FaceFate::kNearOpening: ++out.kept_near_opening; break;
      case FaceFate::kDegenerate: ++out.kept_degenerate; break;
    }
  out.hidden = static_cast<int>(out.faces.size());
  return out;
}

}  // namespace gr
