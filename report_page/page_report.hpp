#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace gr {

// What the report page shows of a run's report.json and of a certificate or validation
// report, typed. read_page_report is the only place that names their keys.
//
// A part (a top-level object such as "ease") may be missing: it stays empty. A part that is
// there must hold every key read here, of its type; a number may be null, as the documents
// write a NaN or an infinity, and reads as empty. Lengths are in the avatar file's units.

/// report.json "fit_error": the written garment's distance to the avatar over its fit faces.
struct ReportFitError {
  std::optional<double> mean;
  std::optional<double> p95;
};

/// report.json "fit": the fit solve.
struct ReportFitSolve {
  std::string status;
  int newton_iterations = 0;
};

/// report.json "inflate": the inflation solve.
struct ReportInflate {
  std::string status;
  int al_rounds = 0;
  int resets = 0;
  int newton_iterations = 0;
};

/// report.json "modelled": what the solve modelled of the garment and the avatar.
struct ReportModelled {
  std::vector<std::string> terms;
  std::string self_contact_where;
  int garment_faces = 0;
  int fit_faces = 0;
  int avatar_faces_total = 0;
  int avatar_faces_modelled = 0;
};

/// report.json "ease": how the fit treated the source's ease and how much the result kept.
struct ReportEase {
  std::string fit;     ///< "ease" or "tight"
  std::string source;  ///< where the source ease came from ("source body", "none")
  int measured_vertices = 0;
  std::optional<double> median_ratio;
  std::optional<double> within_25_percent;  ///< fraction of the measured vertices
};

/// report.json "inherited_crossings": self-crossings the input garment came with.
struct ReportInheritedCrossings {
  int pairs = 0;
  int still_crossing = 0;
  int attached_pieces = 0;
};

/// report.json "untangle": the input's crossings pushed apart before the solve.
struct ReportUntangle {
  int pairs = 0;
  int resolved = 0;
  int remaining = 0;
  std::optional<double> max_displacement;  ///< over the garment's bounding-box diagonal
};

/// report.json "split_non_manifold_edges".
struct ReportSplitEdges {
  int edges = 0;
  int vertex_copies = 0;
};

/// report.json "pierced_faces": input faces the avatar passes through, with its bones.
struct ReportPiercedFaces {
  std::vector<int> left_out_of_contact;  ///< 0-based input faces
  std::vector<int> opened;               ///< 0-based input faces, not written
  std::vector<std::string> bones;
};

/// report.json "shape": the garment's shape change (fractions; scale a ratio).
struct ReportShape {
  std::optional<double> scale;
  std::optional<double> mean_edge_change;
  std::optional<double> p95_edge_change;
  std::optional<double> area_change;
  std::optional<double> loop_displacement;
  std::optional<double> surface_energy_per_area;
};

/// report.json "shrink".
struct ReportShrink {
  std::string mode;
  std::optional<double> depth;  ///< normalized scene units
};

/// One stage's wall time (report.json "seconds").
struct ReportStageTime {
  std::string stage;
  std::optional<double> seconds;
};

/// The parts of a retarget run's report.json the page shows.
struct RunPageReport {
  std::string quality;  ///< empty when missing
  std::optional<bool> certified;
  std::optional<ReportFitError> fit_error;
  std::optional<ReportFitSolve> fit;
  std::optional<ReportInflate> inflate;
  std::optional<ReportModelled> modelled;
  std::optional<ReportEase> ease;
  std::optional<ReportUntangle> untangle;
  std::optional<ReportInheritedCrossings> inherited_crossings;
  std::optional<ReportSplitEdges> split_non_manifold_edges;
  std::optional<ReportPiercedFaces> pierced_faces;
  std::optional<double> min_distance;  ///< "min_distance/avatar_units"
  std::optional<ReportShape> shape;
  std::vector<double> loop_offsets;  ///< "position": per held loop, in lengths of its bone
  std::optional<ReportShrink> shrink;
  /// The stages the page lists, in pipeline order; empty without "seconds".
  std::vector<ReportStageTime> seconds;
  std::optional<double> peak_memory_mb;
  std::vector<std::string> warnings;
};

/// A certificate's or validation report's totals of intersecting face pairs.
struct CertificateCounts {
  int garment_avatar_intersections = 0;
  int garment_self_intersections = 0;
  int garment_garment_intersections = 0;
};

/// Vertices nearer to the avatar than a threshold (with --threshold only).
struct CertificateNearVertices {
  std::optional<double> threshold;
  int count = 0;
};

/// One garment of a certificate or validation report.
struct CertificateGarment {
  std::string path;
  int avatar_intersections = 0;  ///< face pairs
  int self_intersections = 0;    ///< face pairs
  int degenerate_faces = 0;
  std::optional<double> avatar_clearance;  ///< file units
  std::optional<CertificateNearVertices> near_vertices;
};

/// One message of the certificate's "issues".
struct CertificateMessage {
  std::string code;
  std::string severity;  ///< "error", "warning" or "info"
  std::string message;
};

/// The parts of a certificate.json or validation report the page shows.
struct CertificatePageReport {
  std::string kind;  ///< "certificate" or "validation_report"; empty when missing
  std::optional<bool> certified;
  std::optional<CertificateCounts> counts;
  std::vector<CertificateGarment> garments;
  std::vector<CertificateMessage> messages;
};

/// Everything the page shows of its documents.
struct PageReport {
  std::optional<RunPageReport> run;  ///< empty for a validation page (no report.json)
  std::optional<CertificatePageReport> certificate;
};

/// Reads what the page shows from a run's report.json (`report`, null for none) and a
/// certificate or validation report (`certificate`, null for none).
/// @throw std::invalid_argument naming the JSON pointer when a document is not an object, a
///        part lacks a key, or a value has another type than the schema's.
PageReport read_page_report(const nlohmann::json& report,
                            const nlohmann::ordered_json& certificate);

}  // namespace gr
