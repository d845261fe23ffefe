#include "retarget/stages/prepare_stage.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "garment/repairs/non_manifold_edges.hpp"
#include "validate/checks/self_intersections.hpp"

namespace gr {

namespace {

/// Neighbourhood of an inherited crossing whose self pairs are not modelled, in edge rings
/// around each crossing face: one ring leaves pairs a fraction of an edge from the
/// crossing line inside the barrier at the start.
constexpr int kTangleRings = 2;

/// What the repairs work on, and where each puts what it did.
struct Repairing {
  Scene& scene;
  const ScenePaths& paths;
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
constexpr Repair kRepairsNormalized[] = {keep_crossings, find_pierced_faces};

/// The scene in normalized units, rounded to the lattice unless that makes the garment
/// cross itself more than its exact coordinates do; `crossing_pairs` gets its crossings.
NormalizedScene normalize(const Scene& scene, double thinnest_barrier,
                          std::vector<FacePair>& crossing_pairs) {
  NormalizedScene normalized = make_normalized_scene(scene, lattice_spacing(thinnest_barrier));
  require_comparable_sizes(scene, normalized);
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

}  // namespace

PrepareOutput run_prepare(const PrepareInput& input, const PrepareOptions& options,
                          Progress& progress) {
  const StageTimer timer;
  Scene& scene = input.scene;
  PrepareOutput out;
  Repairing repairing{scene, input.paths, out, {}};
  for (const Repair repair : kRepairsAsRead) repair(repairing);
  out.normalized = normalize(scene, options.thinnest_barrier, repairing.crossing_pairs);
  const NormalizedScene& normalized = out.normalized;
  for (const Repair repair : kRepairsNormalized) repair(repairing);

  NormalizeReport& report = out.report;
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
  const InheritedReport& kept = out.repairs.crossings;
  if (kept.pairs > 0)
    progress.warn(fmt::format(
        "the garment crosses itself as given ({} face pairs, e.g. faces {} and {}, 1-based): the "
        "crossings are kept as inherited, their {} vertices around them left out of self "
        "contact, and the certificate counts only new ones",
        kept.pairs, kept.document_pairs.front().first + 1, kept.document_pairs.front().second + 1,
        kept.tangled_vertices));
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
