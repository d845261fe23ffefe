#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "report_page/page_data.hpp"

namespace gr {

/// The scene part of a page as its script reads it: units, heat range, colours, view
/// frame, and every mesh quantized and base64-encoded (see mesh_encoding.hpp).
/// @pre every garment's shapes have the garment's vertex count, one distance per vertex,
///      and marked faces and no-fit entries within its faces.
nlohmann::ordered_json report_page_scene(const ReportPageData& data);

/// A self-contained HTML report: an interactive 3D view (three.js, orbit and zoom) of the
/// avatar and the garments coloured by distance to the body, with a legend, the no-fit
/// and marked faces highlighted and a toggle between the shapes of a garment; beside it
/// the numbers of `data.report` (stage times, fit error, clearance, shape change,
/// warnings) and the verdict of `data.certificate`, and both documents in full; at the
/// end the three.js licence. It opens from disk and makes no network request: script,
/// style and data are inside the file.
/// @throw std::invalid_argument when the data breaks report_page_scene's preconditions.
std::string report_page_html(const ReportPageData& data);

/// Writes report_page_html(data) to `path` atomically.
/// @throw std::invalid_argument as report_page_html; OutputError when it cannot be written.
void write_report_page(const std::string& path, const ReportPageData& data);

}  // namespace gr
