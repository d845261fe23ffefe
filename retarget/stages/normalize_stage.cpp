#include "retarget/stages/normalize_stage.hpp"

#include <algorithm>
#include <cmath>

#include "validate/checks/self_intersections.hpp"

namespace gr {

namespace {

/// Neighbourhood of an inherited crossing whose self pairs are not modelled, in edge rings
/// around each crossing face: one ring leaves pairs a fraction of an edge from the
/// crossing line inside the barrier at the start.
constexpr int kTangleRings = 2;

}  // namespace

NormalizeOutput run_normalize(const NormalizeInput& input, const NormalizeOptions& options,
                              Progress& progress) {
  const StageTimer timer;
  const Scene& scene = input.scene;
  NormalizeOutput out;
  NormalizeReport& report = out.report;
  out.normalized = make_normalized_scene(scene, lattice_spacing(options.thinnest_barrier));
  NormalizedScene& normalized = out.normalized;
  require_comparable_sizes(scene, normalized);
  // Rounding to the lattice can fold a sliver or close a hairline gap: keep the exact
  // coordinates when they cross less.
  SelfIntersections self = find_self_intersecting_face_pairs(normalized.garment);
  if (self.pairs.count > 0 && normalized.lattice > 0.0) {
    NormalizedScene exact = make_normalized_scene(scene);
    SelfIntersections exact_self = find_self_intersecting_face_pairs(exact.garment);
    if (exact_self.pairs.count < self.pairs.count) {
      normalized = std::move(exact);
      self = std::move(exact_self);
    }
  }
  // The copies of a split edge lie on their originals: their neighbourhood is a tangle too.
  std::vector<std::vector<int>> split_sites;
  for (const auto& [copy, original] : scene.garment_ties) split_sites.push_back({copy, original});
  InheritedCrossings& inherited = out.inherited;
  inherited =
      tangles_of(normalized.garment, std::move(self.pairs.pairs), kTangleRings, split_sites);
  inherited.attachments =
      attach_crossing_pieces(normalized.garment, inherited.pairs, layer_of_garment_faces(scene),
                             report.inherited.attached_pieces);
  report.split_edges = scene.split_edges;
  report.split_copies = static_cast<int>(scene.garment_ties.size());
  InheritedReport& kept = report.inherited;
  kept.pairs = static_cast<int>(inherited.pairs.size());
  kept.tangles = inherited.tangle_count;
  kept.tangled_vertices = inherited.tangled_vertices;
  const auto& face_to_obj = scene.garment.face_to_obj;
  for (const FacePair& p : inherited.pairs) {
    const int a = face_to_obj[static_cast<std::size_t>(p.first)];
    const int b = face_to_obj[static_cast<std::size_t>(p.second)];
    kept.document_pairs.push_back({std::min(a, b), std::max(a, b)});
  }
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
