#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "report_page/page_data.hpp"
#include "retarget/report.hpp"
#include "retarget/scene/normalization.hpp"
#include "retarget/scene/scene.hpp"
#include "validate/certify/certificate.hpp"

namespace gr {

/// The report page of a finished retarget run: the avatar, the garment as given (placed in
/// the avatar's frame) and as written, each coloured by its distance to the avatar, the
/// input's faces that cross the avatar and the output's that the certificate found
/// marked, the no-fit faces, and the report's and certificate's numbers. Everything is
/// in the avatar file's frame and units.
/// @param scene, frames the run's inputs and normalization.
/// @param certificate the certification of the written garment (its meshes are the files).
/// @param report the run's report as written to report.json.
ReportPageData retarget_page_data(const Scene& scene, const Normalization& frames,
                                  const Certificate& certificate, const RetargetReport& report);

/// Writes OUT/report.html and, with `stills`, OUT/front.png and OUT/side.png (the written
/// garment on the avatar, rendered without a browser) for a finished run.
/// @throw OutputError when a file cannot be written.
void write_retarget_pages(const std::string& out_dir, bool stills, const Scene& scene,
                          const Normalization& frames, const Certificate& certificate,
                          const RetargetReport& report);

/// The page of `garment-retarget validate --html`: the avatar and every garment as given,
/// coloured by distance to the avatar, with the faces the validation found intersecting
/// or degenerate marked, and `report` (the validation report) beside the view.
/// @throw OutputError when the file cannot be written.
void write_validation_page(const std::string& path, const Validation& validation,
                           const nlohmann::ordered_json& report);

}  // namespace gr
