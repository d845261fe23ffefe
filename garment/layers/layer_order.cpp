#include "garment/layers/layer_order.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

#include <tbb/parallel_for.h>

#include "core/mesh/boundary_loops.hpp"
#include "core/skeleton/skin_matching.hpp"
#include "garment/layers/surface_rays.hpp"
#include "shrink/level_set/triangle_tree.hpp"

namespace gr {

namespace {

/// Per layer, its position in `order` (-1 when left out).
/// @throw std::invalid_argument for an id out of [0, layer_count) or repeated.
std::vector<int> ranks_of(const std::vector<int>& order, int layer_count, const char* what) {
  std::vector<int> rank(static_cast<std::size_t>(layer_count), -1);
  for (std::size_t i = 0; i < order.size(); ++i) {
    const int layer = order[i];
    if (layer < 0 || layer >= layer_count)
      throw std::invalid_argument(std::string(what) + ": layer " + std::to_string(layer) +
                                  " is out of range [0, " + std::to_string(layer_count) + ")");
    if (rank[static_cast<std::size_t>(layer)] >= 0)
      throw std::invalid_argument(std::string(what) + ": layer " + std::to_string(layer) +
                                  " is named twice");
    rank[static_cast<std::size_t>(layer)] = static_cast<int>(i);
  }
  return rank;
}

/// Per bone, the bones at most `hops` apart from it (sharing a joint: one apart), as a
/// bones × bones table of flags.
std::vector<char> bones_within(const Skeleton& skeleton, int hops) {
  const auto count = static_cast<std::size_t>(skeleton.bones.rows());
  std::vector<std::vector<std::size_t>> at_joint(static_cast<std::size_t>(skeleton.joints.rows()));
  for (std::size_t b = 0; b < count; ++b)
    for (int end = 0; end < 2; ++end)
      at_joint[static_cast<std::size_t>(skeleton.bones(static_cast<Eigen::Index>(b), end))]
          .push_back(b);
  std::vector<char> near(count * count, 0);
  for (std::size_t from = 0; from < count; ++from) {
    std::vector<std::size_t> reached{from};
    near[from * count + from] = 1;
    for (int hop = 0; hop < hops; ++hop) {
      std::vector<std::size_t> next;
      for (const std::size_t b : reached)
        for (int end = 0; end < 2; ++end)
          for (const std::size_t other : at_joint[static_cast<std::size_t>(
                   skeleton.bones(static_cast<Eigen::Index>(b), end))])
            if (!near[from * count + other]) {
              near[from * count + other] = 1;
              next.push_back(other);
            }
      reached = std::move(next);
    }
  }
  return near;
}

/// Each layer's first hit on one ray, by distance then layer (see measure_layer_order).
/// @param elsewhere whether a point on the ray lies around another part of the body than
///        the ray's own: the ray stops before it.
std::vector<LayerHit> first_layer_hits(const SurfaceRays& garments, const SurfaceRays& body,
                                       const std::vector<int>& face_layer, int layer_count,
                                       const Vector3d& origin, const Vector3d& direction,
                                       const std::function<bool(const Vector3d&)>& elsewhere) {
  const std::vector<RayHit> hits = garments.hits(origin, direction);
  if (hits.empty()) return {};
  const double first = hits.front().distance;
  double stop = std::numeric_limits<double>::infinity();
  for (const RayHit& hit : body.hits(origin, direction))
    if (hit.distance > first) {
      stop = hit.distance;
      break;
    }
  std::vector<char> seen(static_cast<std::size_t>(layer_count), 0);
  std::vector<LayerHit> out;
  for (const RayHit& hit : hits) {
    if (hit.distance >= stop || (elsewhere && elsewhere(origin + hit.distance * direction))) break;
    const int layer = face_layer[static_cast<std::size_t>(hit.face)];
    if (seen[static_cast<std::size_t>(layer)]) continue;
    seen[static_cast<std::size_t>(layer)] = 1;
    out.push_back({layer, hit.distance, hit.face});
  }
  // Hits come by distance then face: equal distances are put in layer order.
  std::stable_sort(out.begin(), out.end(), [](const LayerHit& a, const LayerHit& b) {
    return a.distance != b.distance ? a.distance < b.distance : a.layer < b.layer;
  });
  return out;
}

/// The point of `to`'s face `face` at the barycentric coordinates that `point` has on the
/// same face of `from`.
Vector3d carry_point(const TriangleMesh& from, const TriangleMesh& to, int face,
                     const Vector3d& point) {
  const auto corner = [face](const TriangleMesh& mesh, int k) -> Vector3d {
    return mesh.vertices.row(mesh.faces(face, k)).transpose();
  };
  const Vector3d a = corner(from, 0), e1 = corner(from, 1) - a, e2 = corner(from, 2) - a;
  const Vector3d d = point - a;
  const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2);
  const double det = d11 * d22 - d12 * d12;
  if (!(det > 0.0)) return corner(to, 0);  // a sliver: any corner is on it
  const double u = (d22 * e1.dot(d) - d12 * e2.dot(d)) / det;
  const double v = (d11 * e2.dot(d) - d12 * e1.dot(d)) / det;
  const Vector3d b = corner(to, 0);
  return b + u * (corner(to, 1) - b) + v * (corner(to, 2) - b);
}

}  // namespace

SourceOrderCheck rays_reordered_from_source(const LayerOrderMeasure& measure,
                                            const TriangleMesh& result, const TriangleMesh& source,
                                            const TriangleMesh& source_body, double tolerance,
                                            const std::vector<char>& unordered_faces) {
  if (result.faces != source.faces || result.vertices.rows() != source.vertices.rows())
    throw std::invalid_argument(
        "rays_reordered_from_source: result and source must be one surface");
  if (source_body.faces.rows() == 0)
    throw std::invalid_argument("rays_reordered_from_source: the source body has no face");
  if (!(tolerance >= 0.0))
    throw std::invalid_argument("rays_reordered_from_source: negative tolerance");
  if (!unordered_faces.empty() &&
      static_cast<Eigen::Index>(unordered_faces.size()) != result.faces.rows())
    throw std::invalid_argument(
        "rays_reordered_from_source: unordered_faces must hold one flag per face");
  const TriangleTree body(source_body);
  const std::vector<bool> cut = faces_on_open_edges(source_body.faces);
  const double no_depth = std::numeric_limits<double>::quiet_NaN();
  std::vector<char> reordered(measure.several.size(), 0), compared(measure.several.size(), 0);
  tbb::parallel_for(std::size_t(0), measure.several.size(), [&](std::size_t r) {
    const RayLayers& ray = measure.several[r];
    std::vector<double> depth;
    std::vector<Vector3d> on_source;
    for (const LayerHit& hit : ray.first_hits) {
      const Vector3d on_result = ray.origin + hit.distance * ray.direction;
      on_source.push_back(carry_point(result, source, hit.face, on_result));
      int nearest = -1;
      depth.push_back(std::sqrt(body.distance_sq(on_source.back(), &nearest)));
      if ((!unordered_faces.empty() && unordered_faces[static_cast<std::size_t>(hit.face)]) ||
          (nearest >= 0 && cut[static_cast<std::size_t>(nearest)]))
        depth.back() = no_depth;  // compares false below
    }
    compared[r] =
        std::count_if(depth.begin(), depth.end(), [](double d) { return !std::isnan(d); }) >= 2;
    for (std::size_t i = 0; i < depth.size() && !reordered[r]; ++i)
      for (std::size_t j = i + 1; j < depth.size(); ++j)
        // Points that lay over one another on the source: apart by at most twice their
        // difference in depth (within 60° of the body's normal).
        if (ray.first_hits[i].distance < ray.first_hits[j].distance &&
            depth[i] > depth[j] + tolerance &&
            (on_source[i] - on_source[j]).norm() <= 2.0 * (depth[i] - depth[j])) {
          reordered[r] = 1;
          break;
        }
  });
  SourceOrderCheck out;
  out.rays_checked = static_cast<int>(measure.several.size());
  out.rays_compared = static_cast<int>(std::count(compared.begin(), compared.end(), 1));
  out.reordered = static_cast<int>(std::count(reordered.begin(), reordered.end(), 1));
  return out;
}

LayeredOutfit merge_layers(const std::vector<TriangleMesh>& garments) {
  Eigen::Index vertices = 0, faces = 0;
  for (const TriangleMesh& g : garments) {
    vertices += g.vertices.rows();
    faces += g.faces.rows();
  }
  LayeredOutfit out;
  out.surface.vertices.resize(vertices, 3);
  out.surface.faces.resize(faces, 3);
  out.face_layer.reserve(static_cast<std::size_t>(faces));
  out.layer_count = static_cast<int>(garments.size());
  Eigen::Index v0 = 0, f0 = 0;
  for (std::size_t layer = 0; layer < garments.size(); ++layer) {
    const TriangleMesh& g = garments[layer];
    out.surface.vertices.middleRows(v0, g.vertices.rows()) = g.vertices;
    out.surface.faces.middleRows(f0, g.faces.rows()) = g.faces.array() + static_cast<int>(v0);
    out.face_layer.insert(out.face_layer.end(), static_cast<std::size_t>(g.faces.rows()),
                          static_cast<int>(layer));
    v0 += g.vertices.rows();
    f0 += g.faces.rows();
  }
  return out;
}

BodyRays rays_from_skeleton(const Skeleton& skeleton, const BodyRayOptions& options) {
  const int samples = options.samples_per_bone, around = options.directions_per_sample;
  if (samples < 1 || around < 1)
    throw std::invalid_argument(
        "rays_from_skeleton: samples_per_bone and directions_per_sample must be at least 1");
  std::vector<Eigen::Index> bones;
  for (Eigen::Index b = 0; b < skeleton.bones.rows(); ++b)
    if (skeleton.joints.row(skeleton.bones(b, 0)) != skeleton.joints.row(skeleton.bones(b, 1)))
      bones.push_back(b);
  const auto rows = static_cast<Eigen::Index>(bones.size()) * samples * around;
  BodyRays out{MatrixX3d(rows, 3), MatrixX3d(rows, 3), skeleton, {}};
  out.bone.reserve(static_cast<std::size_t>(rows));
  Eigen::Index row = 0;
  for (const Eigen::Index b : bones) {
    const Vector3d a = skeleton.joints.row(skeleton.bones(b, 0)).transpose();
    const Vector3d axis = skeleton.joints.row(skeleton.bones(b, 1)).transpose() - a;
    const Vector3d u = unit_perpendicular(axis), v = axis.normalized().cross(u);
    for (int i = 0; i < samples; ++i) {
      const Vector3d origin = a + (i + 0.5) / samples * axis;
      for (int k = 0; k < around; ++k, ++row) {
        const double angle = 2.0 * M_PI * k / around;
        out.origins.row(row) = origin.transpose();
        out.directions.row(row) = (std::cos(angle) * u + std::sin(angle) * v).transpose();
        out.bone.push_back(static_cast<int>(b));
      }
    }
  }
  return out;
}

BodyRays rays_from_body_faces(const TriangleMesh& body, const BodyRayOptions& options) {
  if (options.max_face_rays < 1 || !(options.face_offset >= 0.0))
    throw std::invalid_argument(
        "rays_from_body_faces: max_face_rays must be at least 1 and face_offset non-negative");
  const FaceFrames frames = face_frames(body);
  std::vector<Eigen::Index> faces;
  for (Eigen::Index f = 0; f < body.faces.rows(); ++f)
    if (!frames.normals.row(f).isZero()) faces.push_back(f);
  const auto n = static_cast<long long>(faces.size());
  const long long count = std::min<long long>(n, options.max_face_rays);
  const double offset =
      body.vertices.rows() > 0
          ? options.face_offset *
                (body.vertices.colwise().maxCoeff() - body.vertices.colwise().minCoeff()).norm()
          : 0.0;
  BodyRays out{MatrixX3d(count, 3), MatrixX3d(count, 3), std::nullopt, {}};
  for (long long i = 0; i < count; ++i) {
    const Eigen::Index f = faces[static_cast<std::size_t>(i * n / count)];
    out.directions.row(i) = frames.normals.row(f);
    out.origins.row(i) = frames.centroids.row(f) + offset * frames.normals.row(f);
  }
  return out;
}

LayerOrderMeasure measure_layer_order(const LayeredOutfit& outfit, const TriangleMesh& body,
                                      const BodyRays& rays) {
  const int layers = outfit.layer_count;
  if (layers < 0 ||
      static_cast<Eigen::Index>(outfit.face_layer.size()) != outfit.surface.faces.rows())
    throw std::invalid_argument("measure_layer_order: face_layer must hold one layer per face");
  for (const int layer : outfit.face_layer)
    if (layer < 0 || layer >= layers)
      throw std::invalid_argument("measure_layer_order: face layer " + std::to_string(layer) +
                                  " is out of range [0, " + std::to_string(layers) + ")");
  if (rays.origins.rows() != rays.directions.rows())
    throw std::invalid_argument("measure_layer_order: as many ray directions as origins");

  const bool from_bones = rays.skeleton && rays.skeleton->bones.rows() > 0;
  if (from_bones && (static_cast<Eigen::Index>(rays.bone.size()) != rays.origins.rows() ||
                     std::any_of(rays.bone.begin(), rays.bone.end(),
                                 [&](int b) { return b < 0 || b >= rays.skeleton->bones.rows(); })))
    throw std::invalid_argument("measure_layer_order: one bone of the skeleton per ray");
  const std::vector<char> near =
      from_bones ? bones_within(*rays.skeleton, kRayBoneHops) : std::vector<char>{};
  const auto bone_count = from_bones ? static_cast<std::size_t>(rays.skeleton->bones.rows()) : 0;

  const SurfaceRays garments(outfit.surface), body_rays(body);
  const Eigen::Index count = rays.origins.rows();
  std::vector<std::vector<LayerHit>> per_ray(static_cast<std::size_t>(count));
  tbb::parallel_for(Eigen::Index(0), count, [&](Eigen::Index r) {
    std::function<bool(const Vector3d&)> elsewhere;
    if (from_bones) {
      const auto own = static_cast<std::size_t>(rays.bone[static_cast<std::size_t>(r)]);
      elsewhere = [&, own](const Vector3d& point) {
        const auto nearest = static_cast<std::size_t>(nearest_bone(*rays.skeleton, point).first);
        return !near[own * bone_count + nearest];
      };
    }
    per_ray[static_cast<std::size_t>(r)] = first_layer_hits(
        garments, body_rays, outfit.face_layer, layers, rays.origins.row(r).transpose(),
        rays.directions.row(r).transpose(), elsewhere);
  });

  LayerOrderMeasure out;
  out.layer_count = layers;
  out.rays_cast = static_cast<int>(count);
  out.before = Eigen::MatrixXi::Zero(layers, layers);
  for (Eigen::Index r = 0; r < count; ++r) {
    std::vector<LayerHit>& hits = per_ray[static_cast<std::size_t>(r)];
    if (hits.size() < 2) continue;
    for (std::size_t i = 0; i < hits.size(); ++i)
      for (std::size_t j = i + 1; j < hits.size(); ++j)
        if (hits[i].distance < hits[j].distance) ++out.before(hits[i].layer, hits[j].layer);
    ++out.rays_meeting_several;
    out.several.push_back({static_cast<int>(r), rays.origins.row(r).transpose(),
                           rays.directions.row(r).transpose(), std::move(hits)});
  }
  return out;
}

OutOfOrderRays rays_out_of_order(const LayerOrderMeasure& measure,
                                 const std::vector<int>& inside_to_outside, int max_examples) {
  if (max_examples < 0) throw std::invalid_argument("rays_out_of_order: negative max_examples");
  const std::vector<int> rank =
      ranks_of(inside_to_outside, measure.layer_count, "rays_out_of_order");
  OutOfOrderRays out;
  for (const RayLayers& ray : measure.several) {
    std::vector<LayerHit> ordered;  // the hits of layers in the order, by distance
    for (const LayerHit& hit : ray.first_hits)
      if (rank[static_cast<std::size_t>(hit.layer)] >= 0) ordered.push_back(hit);
    if (ordered.size() < 2) continue;
    ++out.rays_checked;
    const LayerHit* outer = nullptr;
    const LayerHit* inner = nullptr;
    for (std::size_t i = 0; i < ordered.size() && !outer; ++i)
      for (std::size_t j = i + 1; j < ordered.size(); ++j)
        if (ordered[i].distance < ordered[j].distance &&
            rank[static_cast<std::size_t>(ordered[i].layer)] >
                rank[static_cast<std::size_t>(ordered[j].layer)]) {
          outer = &ordered[i];
          inner = &ordered[j];
          break;
        }
    if (!outer) continue;
    ++out.out_of_order;
    if (static_cast<int>(out.examples.size()) < max_examples)
      out.examples.push_back({ray.ray, ray.origin, ray.direction, outer->layer, inner->layer,
                              ray.origin + outer->distance * ray.direction,
                              ray.origin + inner->distance * ray.direction});
  }
  return out;
}

std::vector<int> layer_order_from_votes(const Eigen::MatrixXi& before,
                                        const std::vector<int>& given_order) {
  if (before.rows() != before.cols())
    throw std::invalid_argument("layer_order_from_votes: the votes must be a square matrix");
  const auto n = static_cast<int>(before.rows());
  const std::vector<int> rank = ranks_of(given_order, n, "layer_order_from_votes");
  if (static_cast<int>(given_order.size()) != n)
    throw std::invalid_argument("layer_order_from_votes: the given order must name every layer");
  const auto inside = [&](int a, int b) { return before(a, b) > before(b, a); };
  const auto meets_another = [&](int a) {
    for (int b = 0; b < n; ++b)
      if (b != a && (before(a, b) > 0 || before(b, a) > 0)) return true;
    return false;
  };

  std::vector<int> remaining;  // the layers that meet another, in the given order
  for (const int layer : given_order)
    if (meets_another(layer)) remaining.push_back(layer);
  std::vector<int> placed;
  while (!remaining.empty()) {
    const auto has_inner = [&](int a) {
      return std::any_of(remaining.begin(), remaining.end(), [&](int b) { return inside(b, a); });
    };
    auto next = std::find_if_not(remaining.begin(), remaining.end(), has_inner);
    if (next == remaining.end()) {
      const auto copeland = [&](int a) {
        int score = 0;
        for (const int b : remaining) score += inside(a, b) - inside(b, a);
        return score;
      };
      int best = std::numeric_limits<int>::min();
      for (auto it = remaining.begin(); it != remaining.end(); ++it)
        if (const int score = copeland(*it); score > best) {
          best = score;
          next = it;
        }
    }
    placed.push_back(*next);
    remaining.erase(next);
  }

  std::vector<int> order = given_order;
  std::size_t k = 0;
  for (int& slot : order)
    if (meets_another(slot)) slot = placed[k++];
  return order;
}

}  // namespace gr
