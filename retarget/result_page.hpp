#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "report_page/page_data.hpp"
#include "retarget/animation/animation_check.hpp"
#include "retarget/report.hpp"
#include "retarget/scene/normalization.hpp"
#include "retarget/scene/scene.hpp"
#include "validate/certify/certificate.hpp"

namespace gr {

/// Which of `clips` a page plays: the one with the most crossing frames, then the most pairs
/// in its worst frame, the first of equals.
/// @pre `clips` is not empty.
std::size_t page_clip(const std::vector<const ClipFindings*>& clips);

/// A clip for the page's frame slider: per frame its pair counts and crossing faces from
/// `findings`, the meshes from `poses` (as check_clip posed them), and each garment
/// vertex's distance to the posed avatar (whose faces are `avatar_faces`).
/// @param clip_count how many clips were checked (the page names the one it plays).
/// @pre `poses` are check_clip's for `findings`.
PageAnimation page_animation(const ClipFindings& findings, const ClipPoses& poses,
                             const MatrixX3i& avatar_faces, std::size_t clip_count);

/// The report page of a finished retarget run: the avatar, the garment as given (placed in
/// the avatar's frame) and as written, each coloured by its distance to the avatar, the
/// input's faces that cross the avatar and the output's that the certificate found
/// marked, the no-fit faces, and the report's and certificate's numbers. Everything is
/// in the avatar file's frame and units. With clips played (`report.animation`), the page
/// plays the written files through page_clip's clip as the animate stage's last check
/// posed them.
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
/// or degenerate marked, and `report` (the validation report) beside the view; with
/// `animation`, the frame slider that plays it.
/// @throw OutputError when the file cannot be written.
void write_validation_page(const std::string& path, const Validation& validation,
                           const nlohmann::ordered_json& report,
                           std::optional<PageAnimation> animation = std::nullopt);

}  // namespace gr
