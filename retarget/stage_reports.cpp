#include "retarget/stage_reports.hpp"

#include <algorithm>
#include <cmath>

namespace gr {

void record_inputs(RetargetReport& report, const ReadOutput& read, const PrepareOutput& prepare,
                   const InferOutput& inferred) {
  report.estimated_memory_mb = read.estimated_memory_mb;
  report.shrink.mode = read.shrink_mode;
  report.seconds.read = read.seconds;
  report.pose = read.pose;
  report.normalize = prepare.report;
  report.repairs = prepare.repairs;
  double& min_separation = report.parameters.solver.ccd.min_separation;
  min_separation = std::max(min_separation, prepare.ccd_min_separation);
  report.seconds.normalize = prepare.seconds;
  report.inferred = inferred.inferred;
  report.ease = inferred.ease;
  report.pose.source_body_posed = inferred.source_body_posed;
}

void record_shrink(RetargetReport& report, const ShrinkOutput& shrink,
                   const InferOutput& inferred) {
  const nlohmann::json conflict = report.shrink.conflict;
  report.shrink = shrink.report;
  report.shrink.conflict = conflict;
  report.repairs.pierced.shrinks = shrink.pierced.shrinks;
  report.repairs.pierced.bones = shrink.pierced.bones;
  report.repairs.pierced.document_faces = shrink.pierced.document_faces;
  report.seconds.shrink = inferred.binding_seconds + shrink.seconds;
}

void record_modelled(RetargetReport& report, const SolverScene& solver) {
  const RetargetParameters& parameters = report.parameters.solver;
  report.fit.fit_faces =
      static_cast<int>(std::count(solver.fit_faces.begin(), solver.fit_faces.end(), true));
  report.fit.avatar_faces_modelled = solver.avatar_faces_modelled;
  report.fit.self_contact = parameters.self_contact;
  report.fit.self_contact_everywhere = parameters.self_contact_everywhere;
}

void record_written(RetargetReport& report, const WriteOutput& written) {
  report.repairs.pierced.opened_document_faces = written.opened_document_faces;
  report.skin = written.skin;
  report.seconds.write = written.seconds;
}

void record_certified(RetargetReport& report, const CertifyOutput& certified) {
  report.certify = certified.report;
  report.seconds.certify = certified.seconds;
  if (report.ease.source_known) {
    report.ease.measure = certified.ease;
    report.ease.document_ratio = certified.ease_document_ratio;
  }
  report.repairs.crossings.still_crossing = certified.inherited_still_crossing;
  // The solver sees only pairs within dhat; a garment that ended further away takes the
  // certificate's clearance, so the report never holds an infinity.
  if (!std::isfinite(report.fit.min_distance))
    report.fit.min_distance =
        certified.certificate.validation.result.totals().smallest_avatar_clearance *
        report.normalize.scene_scale;
}

void record_outfit(RetargetReport& report, OutfitReport outfit, const Scene& scene,
                   const WriteOutput& written, const std::vector<std::string>& recorded_paths,
                   const CertifyOutput& certified) {
  for (std::size_t k = 0; k < scene.layers.size(); ++k) {
    const GarmentLayer& layer = scene.layers[k];
    outfit.layers.push_back({layer.name, layer.path, layer.mesh, layer.face_count,
                             recorded_paths[k], written.garments[k].mesh,
                             certified.layer_shapes[k]});
  }
  report.seconds.certify += outfit.seconds;
  report.outfit = std::move(outfit);
}

}  // namespace gr
