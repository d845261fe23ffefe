#include "retarget/stages/prepare_stage.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <optional>

#include <fmt/format.h>

#include "core/common/errors.hpp"
#include "core/mesh/pieces.hpp"
#include "garment/layers/layer_order.hpp"
#include "garment/repairs/non_manifold_edges.hpp"
#include "garment/repairs/untangle.hpp"
#include "retarget/scene/avatar_coverage.hpp"
#include "validate/checks/self_intersections.hpp"
#include "validate/measure/shape_change.hpp"

namespace gr {

namespace {

/// Neighbourhood of an inherited crossing whose self pairs are not modelled, in edge rings
/// around each crossing face: one ring leaves pairs a fraction of an edge from the
/// crossing line inside the barrier at the start.
constexpr int kTangleRings = 2;

/// The untangle's reach, in barrier supports: it pushes crossing faces this far apart (a
/// gap the barrier then holds without starting near its singularity), faces of two layers
/// of an outfit kUntangleLayerSeparation apart, and moves no vertex further than
/// kUntangleBudget (about 3 cm on a body 1.7 m tall at the default support). Layers parted
/// beyond the barrier's support start the solve free of each other: parted to half of it,
/// the goblin's skirt and puffer pressed on each other from the start and took 795
/// inflation steps, parted to 1.5 supports 92 (bench/results/outfits.md).
constexpr double kUntangleSeparation = 0.5;
constexpr double kUntangleLayerSeparation = 1.5;
constexpr double kUntangleBudget = 10.0;
/// Points per bone that stand for the body when the untangle tells inside from outside.
constexpr int kBonePoints = 8;
/// Two pieces of one garment are in order when rays from the body meet one first at least
/// kPieceVotes times and more than kPieceMajority times as often as the other.
constexpr int kPieceVotes = 3;
constexpr int kPieceMajority = 2;

/// What the repairs work on, and where each puts what it did.
struct Repairing {
  Scene& scene;
  const ScenePaths& paths;
  const PrepareOptions& options;
  PrepareOutput& out;
  /// The normalized garment's face pairs that cross, as given.
  std::vector<FacePair> crossing_pairs;
};

/// Edges of more than two faces split for the solver (on the scene as read).
void split_edges(Repairing& r) {
  NonManifoldReport& report = r.out.repairs.non_manifold;
  report = split_non_manifold_edges(r.scene.garment, r.scene.garment_ties);
  if (report.edges > 0)
    r.scene.warnings.push_back(fmt::format(
        "{}: {} edges shared by more than two faces were split for the solver ({} vertex copies, "
        "tied to their originals); the written file welds them back",
        r.paths.garment, report.edges, report.vertex_copies));
}

/// Points inside the body: along the source bones, else the avatar's vertices.
MatrixX3d body_points(const NormalizedScene& normalized) {
  if (!normalized.source_skeleton) return normalized.avatar.vertices;
  const Skeleton& skeleton = *normalized.source_skeleton;
  MatrixX3d points(skeleton.bones.rows() * (kBonePoints + 1), 3);
  for (Eigen::Index b = 0; b < skeleton.bones.rows(); ++b)
    for (int i = 0; i <= kBonePoints; ++i) {
      const double t = static_cast<double>(i) / kBonePoints;
      points.row(b * (kBonePoints + 1) + i) =
          (1.0 - t) * skeleton.joints.row(skeleton.bones(b, 0)) +
          t * skeleton.joints.row(skeleton.bones(b, 1));
    }
  return points;
}

/// Where rays from the source bones (else from the avatar's faces) meet the parts of
/// `outfit` (its face_layer: a part per face) first.
LayerOrderMeasure measure_on_source(const NormalizedScene& normalized,
                                    const LayeredOutfit& outfit) {
  return normalized.source_skeleton
             ? measure_layer_order(outfit, TriangleMesh{},
                                   rays_from_skeleton(*normalized.source_skeleton))
             : measure_layer_order(outfit, normalized.avatar,
                                   rays_from_body_faces(normalized.avatar));
}

/// The layers' ranks from the inside (per layer), given or measured on the source.
std::vector<int> layer_ranks(const NormalizedScene& normalized, const std::vector<int>& face_layer,
                             int layer_count, const std::vector<int>& given_order) {
  std::vector<int> order = given_order;
  if (order.empty()) {
    const LayerOrderMeasure measure =
        measure_on_source(normalized, {normalized.garment, face_layer, layer_count});
    order.resize(static_cast<std::size_t>(layer_count));
    std::iota(order.begin(), order.end(), 0);
    if (measure.rays_meeting_several > 0) order = layer_order_from_votes(measure.before, order);
  }
  std::vector<int> rank(static_cast<std::size_t>(layer_count), 0);
  for (std::size_t k = 0; k < order.size(); ++k)
    rank[static_cast<std::size_t>(order[k])] = static_cast<int>(k);
  return rank;
}

/// The untangle's parts, each piece (connected part) of each garment, and their order:
/// garments by the outfit's layer order, pieces of one garment where rays from the body
/// meet one first clearly more often (a shirt's open front over its lining).
void order_parts(const Scene& scene, const NormalizedScene& normalized,
                 const std::vector<int>& face_layer, const std::vector<int>& given_order,
                 const std::vector<FacePair>& pairs, UntangleOptions& options) {
  const TriangleMesh& garment = normalized.garment;
  const std::vector<int> piece = vertex_pieces(garment);
  std::map<std::pair<int, int>, int> part_of;
  std::vector<int> face_part(static_cast<std::size_t>(garment.faces.rows()));
  std::vector<int> layer_of_part;
  for (Eigen::Index f = 0; f < garment.faces.rows(); ++f) {
    const int layer = face_layer[static_cast<std::size_t>(f)];
    const auto [it, added] = part_of.emplace(
        std::pair<int, int>{layer, piece[static_cast<std::size_t>(garment.faces(f, 0))]},
        static_cast<int>(part_of.size()));
    if (added) layer_of_part.push_back(layer);
    face_part[static_cast<std::size_t>(f)] = it->second;
  }
  const bool between_parts = std::any_of(pairs.begin(), pairs.end(), [&](const FacePair& p) {
    return face_part[static_cast<std::size_t>(p.first)] !=
           face_part[static_cast<std::size_t>(p.second)];
  });
  if (!between_parts) return;
  const auto layer_count = static_cast<int>(scene.layers.size());
  const std::vector<int> rank = layer_count > 1
                                    ? layer_ranks(normalized, face_layer, layer_count, given_order)
                                    : std::vector<int>(1, 0);
  const auto part_count = static_cast<int>(part_of.size());
  const LayerOrderMeasure measure = measure_on_source(normalized, {garment, face_part, part_count});
  Eigen::MatrixXi inside = Eigen::MatrixXi::Zero(part_count, part_count);
  for (int i = 0; i < part_count; ++i)
    for (int j = 0; j < part_count; ++j) {
      const int li = layer_of_part[static_cast<std::size_t>(i)];
      const int lj = layer_of_part[static_cast<std::size_t>(j)];
      const int before = measure.before(i, j), after = measure.before(j, i);
      if (li != lj)
        inside(i, j) =
            rank[static_cast<std::size_t>(li)] < rank[static_cast<std::size_t>(lj)] ? 1 : -1;
      else if (before >= kPieceVotes && before > kPieceMajority * after)
        inside(i, j) = 1;
      else if (after >= kPieceVotes && after > kPieceMajority * before)
        inside(i, j) = -1;
    }
  options.face_part = std::move(face_part);
  options.part_inside = std::move(inside);
  options.part_layer = std::move(layer_of_part);
  options.body_points = body_points(normalized);
}

/// The garment's crossings as given pushed apart, within each garment and between layers;
/// what is left goes on to be kept as inherited.
void untangle(Repairing& r) {
  if (r.crossing_pairs.empty()) return;
  const StageTimer timer;
  NormalizedScene& normalized = r.out.normalized;
  const std::vector<int> face_layer = layer_of_garment_faces(r.scene);
  UntangleOptions options;
  options.separation = kUntangleSeparation * r.options.thinnest_barrier;
  options.layer_separation = kUntangleLayerSeparation * r.options.thinnest_barrier;
  options.max_displacement = kUntangleBudget * r.options.thinnest_barrier;
  options.lattice = normalized.lattice;
  options.pinned.assign(static_cast<std::size_t>(normalized.garment.vertices.rows()), 0);
  for (const auto& [copy, original] : r.scene.garment_ties)
    options.pinned[static_cast<std::size_t>(copy)] =
        options.pinned[static_cast<std::size_t>(original)] = 1;
  order_parts(r.scene, normalized, face_layer, r.options.layer_order, r.crossing_pairs, options);
  Untangled untangled = untangle_crossings(normalized.garment, r.crossing_pairs, options);

  UntangleReport& report = r.out.repairs.untangle;
  report.pairs = untangled.pairs_before;
  report.resolved = untangled.resolved;
  report.left = static_cast<int>(untangled.left.size()) - untangled.added;
  report.added = untangled.added;
  report.remaining = static_cast<int>(untangled.remaining.size());
  report.pushes = untangled.pushes;
  report.moved_vertices = untangled.moved_vertices;
  const auto document_pair = [&](const FacePair& p) {
    const auto& face_to_obj = r.scene.garment.face_to_obj;
    const int a = face_to_obj[static_cast<std::size_t>(p.first)];
    const int b = face_to_obj[static_cast<std::size_t>(p.second)];
    return FacePair{std::min(a, b), std::max(a, b)};
  };
  const auto between_layers = [&](const FacePair& p) {
    return face_layer[static_cast<std::size_t>(p.first)] !=
           face_layer[static_cast<std::size_t>(p.second)];
  };
  for (const FacePair& p : r.crossing_pairs) report.layer_pairs += between_layers(p) ? 1 : 0;
  report.layer_pairs_resolved = report.layer_pairs;
  for (const LeftCrossing& left : untangled.left) {
    report.left_document_pairs.push_back(document_pair(left.pair));
    report.left_reasons.push_back(describe(left));
    if (!left.made) report.layer_pairs_resolved -= between_layers(left.pair) ? 1 : 0;
  }
  if (untangled.moved_vertices > 0) {
    const double diagonal = (normalized.garment.vertices.colwise().maxCoeff() -
                             normalized.garment.vertices.colwise().minCoeff())
                                .norm();
    report.max_displacement = untangled.max_displacement / diagonal;
    report.mean_edge_change =
        measure_shape_change(normalized.garment, untangled.vertices).mean_edge_change;
    report.moved_edge_change =
        moved_edge_change(normalized.garment, normalized.garment.vertices, untangled.vertices);
    normalized.garment_as_given = normalized.garment.vertices;
    normalized.garment.vertices = std::move(untangled.vertices);
  }
  r.crossing_pairs = std::move(untangled.remaining);
  report.seconds = timer.seconds();
}

/// The garment's own crossings kept as inherited, pieces through pieces attached.
void keep_crossings(Repairing& r) {
  const NormalizedScene& normalized = r.out.normalized;
  // The copies of a split edge lie on their originals: their neighbourhood is a tangle too.
  std::vector<std::vector<int>> split_sites;
  for (const auto& [copy, original] : r.scene.garment_ties) split_sites.push_back({copy, original});
  InheritedCrossings& inherited = r.out.inherited;
  InheritedReport& kept = r.out.repairs.crossings;
  inherited =
      tangles_of(normalized.garment, std::move(r.crossing_pairs), kTangleRings, split_sites);
  inherited.attachments = attach_crossing_pieces(
      normalized.garment, inherited.pairs, layer_of_garment_faces(r.scene), kept.attached_pieces);
  kept.pairs = static_cast<int>(inherited.pairs.size());
  kept.tangles = inherited.tangle_count;
  kept.tangled_vertices = inherited.tangled_vertices;
  const auto& face_to_obj = r.scene.garment.face_to_obj;
  for (const FacePair& p : inherited.pairs) {
    const int a = face_to_obj[static_cast<std::size_t>(p.first)];
    const int b = face_to_obj[static_cast<std::size_t>(p.second)];
    kept.document_pairs.push_back({std::min(a, b), std::max(a, b)});
  }
}

/// Faces the source bones pierce: the shrink leaves them out of the avatar contact.
void find_pierced_faces(Repairing& r) {
  const NormalizedScene& normalized = r.out.normalized;
  if (!normalized.source_skeleton) return;
  r.out.pierced =
      pierced_by_bones(normalized.garment, *normalized.source_skeleton, r.scene.joint_names);
  r.out.repairs.pierced.bones = r.out.pierced.bones;
}

using Repair = void (*)(Repairing&);
/// The input repairs in the order they run: on the garment's surface as read, then on the
/// normalized scene. A new repair is its unit in garment/repairs and one line here.
constexpr Repair kRepairsAsRead[] = {split_edges};
constexpr Repair kRepairsNormalized[] = {untangle, keep_crossings, find_pierced_faces};

/// The scene in normalized units, rounded to the lattice unless that makes the garment
/// cross itself more than its exact coordinates do; `crossing_pairs` gets its crossings.
NormalizedScene normalize(const Scene& scene, double thinnest_barrier,
                          std::vector<FacePair>& crossing_pairs) {
  NormalizedScene normalized = make_normalized_scene(scene, lattice_spacing(thinnest_barrier));
  require_comparable_sizes(scene, normalized);
  require_garment_on_avatar(scene, normalized);
  // Rounding to the lattice can fold a sliver or close a hairline gap.
  SelfIntersections self = find_self_intersecting_face_pairs(normalized.garment);
  if (self.pairs.count > 0 && normalized.lattice > 0.0) {
    NormalizedScene exact = make_normalized_scene(scene);
    SelfIntersections exact_self = find_self_intersecting_face_pairs(exact.garment);
    if (exact_self.pairs.count < self.pairs.count) {
      normalized = std::move(exact);
      self = std::move(exact_self);
    }
  }
  crossing_pairs = std::move(self.pairs.pairs);
  return normalized;
}

/// Where the avatar lacks the surface under the garment (measure_avatar_coverage): refused
/// beyond kMaxUncoveredShare of the garment, a warning (returned) beyond kUncoveredWarning.
std::optional<std::string> check_avatar_coverage(const Scene& scene,
                                                 const NormalizedScene& normalized,
                                                 NormalizeReport& report) {
  constexpr double kMaxUncoveredShare = 0.8;
  constexpr double kUncoveredWarning = 0.1;
  const AvatarCoverage coverage = measure_avatar_coverage(normalized);
  report.uncovered_share = coverage.uncovered_share;
  for (const int bone : coverage.uncovered_bones)
    report.uncovered_bones.push_back(
        bone_name(*normalized.target_skeleton, scene.joint_names, bone));
  if (coverage.uncovered_share <= kUncoveredWarning) return std::nullopt;
  constexpr std::size_t kBonesNamed = 3;
  const std::size_t named = std::min(kBonesNamed, report.uncovered_bones.size());
  const std::string where = fmt::format(
      "{:.0f}% of the garment's area lies around bones the avatar has almost no surface around "
      "({}{}): a body cut away under its own clothes, or the mesh of that part not read "
      "(--avatar-mesh)",
      100.0 * coverage.uncovered_share,
      fmt::join(report.uncovered_bones.begin(), report.uncovered_bones.begin() + named, ", "),
      report.uncovered_bones.size() > named ? ", ..." : "");
  if (coverage.uncovered_share > kMaxUncoveredShare)
    throw InputError(scene.avatar_document.source_path, 0,
                     where + "; nothing there to fit the garment to");
  return where + "; the fit has nothing there to rest the garment on";
}

}  // namespace

PrepareOutput run_prepare(const PrepareInput& input, const PrepareOptions& options,
                          Progress& progress) {
  const StageTimer timer;
  Scene& scene = input.scene;
  PrepareOutput out;
  Repairing repairing{scene, input.paths, options, out, {}};
  for (const Repair repair : kRepairsAsRead) repair(repairing);
  out.normalized = normalize(scene, options.thinnest_barrier, repairing.crossing_pairs);
  const NormalizedScene& normalized = out.normalized;
  NormalizeReport& report = out.report;
  const std::optional<std::string> lacking = check_avatar_coverage(scene, normalized, report);
  for (const Repair repair : kRepairsNormalized) repair(repairing);

  report.scene_scale = normalized.normalization.avatar_to_scene.scale;
  report.lattice = normalized.lattice;
  // The solver sees the avatar rounded to the lattice, the certificate the avatar as given.
  // Rounding moves a point of the avatar by at most half a lattice cell's diagonal, so
  // pairs kept a whole diagonal apart stay apart on both (a pair may otherwise creep,
  // a fraction of its gap per CCD-bounded step, to well below the rounding).
  out.ccd_min_separation = std::sqrt(3.0) * normalized.lattice;
  // Progress starts once the inputs are known good, so bad input prints its error alone.
  progress.log("read", "{} on {}", input.paths.garment, input.paths.avatar);
  for (const auto& warning : scene.warnings) progress.warn(warning);
  if (lacking) progress.warn(*lacking);
  const UntangleReport& untangled = out.repairs.untangle;
  if (untangled.pairs > 0)
    progress.log("untangle",
                 "{} of the {} face pairs the garment crosses itself in as given pushed apart, "
                 "{} crossing after it ({} vertices moved, at most {:.2g} of the diagonal, edge "
                 "change {:.3f} where moved) in {:.1f} s",
                 untangled.resolved, untangled.pairs, untangled.remaining, untangled.moved_vertices,
                 untangled.max_displacement, untangled.moved_edge_change, untangled.seconds);
  const InheritedReport& kept = out.repairs.crossings;
  if (kept.pairs > 0)
    progress.warn(fmt::format(
        "the garment crosses itself as given in {} face pairs the untangle left (e.g. faces {} "
        "and {}, 1-based; report.json untangle.left_pairs says why): they are kept as "
        "inherited, only the point and edge pairs touching across them left out of self "
        "contact, and the certificate counts only new ones",
        kept.pairs, kept.document_pairs.front().first + 1, kept.document_pairs.front().second + 1));
  report.garment_vertices = static_cast<int>(normalized.garment.vertices.rows());
  report.garment_faces = static_cast<int>(normalized.garment.faces.rows());
  report.avatar_faces_total = static_cast<int>(normalized.avatar.faces.rows());
  out.seconds = timer.seconds();
  progress.log("scene", "garment {} vertices / {} faces, avatar {} faces, scale {:.6g}",
               report.garment_vertices, report.garment_faces, report.avatar_faces_total,
               report.scene_scale);
  return out;
}

}  // namespace gr
