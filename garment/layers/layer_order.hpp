#pragma once

#include <optional>
#include <vector>

#include "core/common/types.hpp"
#include "core/io/rig_files.hpp"

namespace gr {

/// An outfit: the garments worn together, merged into one mesh whose faces know their layer.
struct LayeredOutfit {
  TriangleMesh surface;         ///< #V×3 / #F×3, every layer's garment
  std::vector<int> face_layer;  ///< #F, the layer of each face, in [0, layer_count)
  int layer_count = 0;
};

/// The garments merged in the order given: garment i is layer i, its vertices and faces
/// follow those of the garments before it.
LayeredOutfit merge_layers(const std::vector<TriangleMesh>& garments);

/// Rays cast from the body outward.
struct BodyRays {
  MatrixX3d origins;     ///< #R×3, the body's units
  MatrixX3d directions;  ///< #R×3, unit length
  /// Rays cast from a skeleton's bones: the skeleton, and per ray the bone it leaves from
  /// (rows of skeleton.bones). Empty for rays from a body's faces.
  std::optional<Skeleton> skeleton;
  std::vector<int> bone;
};

/// How many rays to cast and from where.
struct BodyRayOptions {
  int samples_per_bone = 8;        ///< points along each bone
  int directions_per_sample = 16;  ///< rays around the bone from each point
  /// Rays from the body's faces at most; above it a deterministic subsample of the faces.
  int max_face_rays = 20000;
  /// How far a face ray's origin sits off its face, as a fraction of the body's
  /// bounding-box diagonal: far below any gap a garment keeps to the body, so that the ray
  /// starts between the face and the garment, clear of the face itself.
  double face_offset = 1e-6;
};

/// Rays perpendicular to the bones: on each bone (a, b), `samples_per_bone` points
/// a + t·(b − a) at t = (i + ½) / samples_per_bone (never at a joint, where limbs meet),
/// and from each, `directions_per_sample` directions cos θ·u + sin θ·v at
/// θ = 2πk / directions_per_sample, with u = unit_perpendicular(b − a) (surface_rays.hpp)
/// and v = (b − a)/|b − a| × u. Rows bone by bone, point by point, direction by
/// direction; a zero-length bone gives none. Each ray keeps its bone (BodyRays::bone).
/// @throw std::invalid_argument when samples_per_bone or directions_per_sample is below 1.
BodyRays rays_from_skeleton(const Skeleton& skeleton, const BodyRayOptions& options = {});

/// Rays along the faces' normals (their winding, taken as outward) from their centroids,
/// offset by `face_offset` along the normal. Every face with a non-zero area when there
/// are at most `max_face_rays` of them, else max_face_rays of them, the ⌊i·n / max⌋-th
/// (i = 0 … max − 1) of the n in face order. Rows in face order.
/// @throw std::invalid_argument when max_face_rays is below 1 or face_offset is negative.
BodyRays rays_from_body_faces(const TriangleMesh& body, const BodyRayOptions& options = {});

/// The first hit of one layer on one ray.
struct LayerHit {
  int layer = -1;
  double distance = 0.0;  ///< from the ray's origin, the body's units
  int face = -1;          ///< the face of the outfit's surface met
};

/// A ray that met two or more layers.
struct RayLayers {
  int ray = -1;  ///< row of the BodyRays
  Vector3d origin = Vector3d::Zero(), direction = Vector3d::Zero();
  std::vector<LayerHit> first_hits;  ///< one per layer met, by distance then layer
};

/// The order in which rays from the body meet the layers.
struct LayerOrderMeasure {
  int layer_count = 0;
  int rays_cast = 0;
  int rays_meeting_several = 0;  ///< rays meeting two or more layers
  /// layer_count × layer_count: before(a, b) = the rays on which layer a's first hit is
  /// strictly nearer than layer b's (rays meeting both); zero diagonal.
  Eigen::MatrixXi before;
  std::vector<RayLayers> several;  ///< the rays meeting two or more layers, by ray
};

/// How many bones a garment hit's nearest bone may lie from the bone of the ray that meets
/// it (see measure_layer_order): two, so that a hit around the next bone or the one after
/// it counts (a collar around the neck met by the shoulder's rays).
inline constexpr int kRayBoneHops = 2;

/// Casts `rays` against the outfit and the body (both in the rays' frame). On each ray,
/// only the garment hits from the first one on count, and with a body only those strictly
/// before the first body hit beyond that first garment hit: a ray from the forearm that
/// passes the sleeve and then enters the torso stops there, and the torso's layers behind
/// it do not count. Body hits before the first garment hit (the ray leaving the body) do
/// not stop it. An empty `body` (no face) stops nothing. A ray from a bone also stops
/// before the first garment hit whose nearest bone lies more than kRayBoneHops bones from
/// its own (bones sharing a joint are one apart): where the body is cut away under the clothes, the
/// forearm's ray that passes the sleeve then meets the trousers around the hips, which lie around
/// another part of the body. The same counts for any number of threads.
/// @throw std::invalid_argument when face_layer does not hold one layer in
///        [0, layer_count) per outfit face, the rays' origins and directions differ in
///        count, or rays from a skeleton do not each name one of its bones.
LayerOrderMeasure measure_layer_order(const LayeredOutfit& outfit, const TriangleMesh& body,
                                      const BodyRays& rays);

/// A ray on which the layers are met out of a given order.
struct OutOfOrderRay {
  int ray = -1;  ///< row of the BodyRays
  Vector3d origin = Vector3d::Zero(), direction = Vector3d::Zero();
  int outer_layer = -1;  ///< later in the order, yet met first
  int inner_layer = -1;  ///< earlier in the order, met after it
  Vector3d outer_point = Vector3d::Zero(), inner_point = Vector3d::Zero();  ///< first hits
};

/// The rays that contradict an order.
struct OutOfOrderRays {
  int rays_checked = 0;                 ///< rays meeting two or more of the order's layers
  int out_of_order = 0;                 ///< of those, the rays out of order
  std::vector<OutOfOrderRay> examples;  ///< the first `max_examples` of them, by ray
};

/// The rays out of the order `inside_to_outside` (layer ids, innermost first): those on
/// which some layer later in the order has its first hit strictly before that of a layer
/// earlier in it. Layers left out of the order are ignored. An example names the first
/// such pair along its ray (the nearest outer-layer hit that comes too early).
/// @throw std::invalid_argument for a layer id out of range or repeated, or a negative
///        max_examples.
OutOfOrderRays rays_out_of_order(const LayerOrderMeasure& measure,
                                 const std::vector<int>& inside_to_outside, int max_examples = 5);

/// Rays whose layers come the other way round than on the source.
struct SourceOrderCheck {
  int rays_checked = 0;   ///< rays meeting two or more layers
  int rays_compared = 0;  ///< of those, rays with two hits of known depth (an order to keep)
  int reordered = 0;      ///< of those, the rays with two layers met against the source's order
};

/// Compares the order of each ray's layers with the order of the same garment points on the
/// source. `measure` was taken on `result` (the outfit's surface where the rays were cast);
/// `source` is that outfit at its source positions (the same faces) and `source_body` its
/// body, both in one frame. A ray is reordered when, of two first hits, the one met first
/// lay over the one met after it on the source: further from the source body by more than
/// `tolerance`, and apart by at most twice that difference in depth (one over the other,
/// within 60° of the body's normal). Points closer in depth (layers touching, or crossing
/// as given) or side by side on the source have no order to keep. Local, so that a layer
/// tucked under another where it was tucked on the source is not counted. Nor do hits
/// without a depth: on a face of `unordered_faces` (per face of the outfit; empty: none),
/// such as the tangles around crossings the input came with, or nearest to a face of the
/// body along a cut (an open edge), where the body was cut away under the clothes.
/// @throw std::invalid_argument when the surfaces differ in shape, the body has no face,
///        the tolerance is negative or unordered_faces is neither empty nor one per face.
SourceOrderCheck rays_reordered_from_source(const LayerOrderMeasure& measure,
                                            const TriangleMesh& result, const TriangleMesh& source,
                                            const TriangleMesh& source_body, double tolerance,
                                            const std::vector<char>& unordered_faces = {});

/// An inside-to-outside order from the votes `before` (n × n, as in LayerOrderMeasure):
/// a is inside b when before(a, b) > before(b, a). A layer that meets no other (no vote
/// either way) keeps its slot of `given_order`; the others fill the remaining slots, one at
/// a time from the inside: next comes the earliest of `given_order` with no remaining layer
/// inside it, or, when every remaining layer has one (a cycle), the one with the best
/// Copeland score among the remaining (layers it is inside of minus layers inside it), the
/// earliest of `given_order` on a tie. The same votes and given order always give the same
/// order.
/// @throw std::invalid_argument when `before` is not square or given_order is not a
///        permutation of [0, n).
std::vector<int> layer_order_from_votes(const Eigen::MatrixXi& before,
                                        const std::vector<int>& given_order);

}  // namespace gr
