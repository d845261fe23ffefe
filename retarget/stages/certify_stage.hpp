#pragma once

#include <string>
#include <vector>

#include "garment/fit/ease.hpp"
#include "retarget/report.hpp"
#include "retarget/run/progress.hpp"
#include "retarget/scene/normalization.hpp"
#include "validate/certify/certificate.hpp"

namespace gr {

struct CertifyInput {
  const ScenePaths& paths;  ///< the input garment and avatar files, as given
  const Scene& scene;
  const NormalizedScene& normalized;
  const MatrixX3d& garment;  ///< the written garment (normalized #Vg×3)
  const std::vector<bool>& fit_faces;
  /// The garment's source ease, for the ease measure; null: not measured.
  const SourceEase* source_ease = nullptr;
  /// Per layer (Scene::layers), the garment file as written (staging), the path the
  /// certificate names (the file's final place) and its mesh in a glTF file (empty: its
  /// only one). One garment has one entry.
  std::vector<std::string> written_files;
  std::vector<std::string> recorded_paths;
  std::vector<std::string> written_meshes;
  /// The run's report so far: its parameters, inherited pairs and opened faces go into
  /// the certificate.
  const RetargetReport& report;
};

struct CertifyOptions {
  ShapeThresholds shape_thresholds;  ///< as given; with skeletons only edge changes apply
  Quality quality = Quality::kBalanced;
  double dhat = RetargetParameters{}.dhat;  ///< the ease measure's smallest ease (normalized)
};

struct CertifyOutput {
  Certificate certificate;
  CertifyReport report;
  EaseMeasure ease;  ///< with a source ease; vertices 0 otherwise
  /// Per garment document position (OBJ `v` order), the measured ease ratio; NaN where
  /// none; empty without a source ease.
  std::vector<double> ease_document_ratio;
  int inherited_still_crossing = 0;  ///< of the inherited pairs, those still crossing
  /// An outfit: each layer's own change of shape (Scene::layers' order); empty for one
  /// garment.
  std::vector<ShapeChange> layer_shapes;
  double seconds = 0.0;
};

/// Certify: the written file checked exactly against the avatar file, with the garment's
/// change of shape (each exceeded threshold a warning), its ease and its fit error beside
/// it.
/// @throw InputError when an input file cannot be read back.
CertifyOutput run_certify(const CertifyInput& input, const CertifyOptions& options,
                          Progress& progress);

/// The run's one-line summary: certified or not, intersections, min distance, fit error
/// and time.
std::string certify_summary(const Certificate& certificate, const RetargetReport& report,
                            double total_seconds);

}  // namespace gr
