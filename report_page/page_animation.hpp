#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "report_page/page_data.hpp"

namespace gr {

/// The most bytes the posed positions of a page's clip take before base64 (16-bit
/// coordinates; 4/3 of it in the page): the garments are kept in every frame, the avatar
/// in every `avatar_frame_stride`-th frame within what is left.
constexpr std::size_t kAnimationPositionBytes = std::size_t{12} << 20;

/// Keep the avatar's positions every this many frames (and in the last): 1 when every frame
/// fits in kAnimationPositionBytes beside the garments' frames, else the smallest stride
/// whose key frames fit in what the garments leave (at least a quarter of the budget; when
/// even two frames do not fit, the first and the last).
/// @param frames the clip's sampled frames; vertex counts of the avatar and of all garments.
std::size_t avatar_frame_stride(std::size_t frames, std::size_t avatar_vertices,
                                std::size_t garment_vertices);

/// The frames of the avatar kept on the page: 0, stride, 2 stride, ... and the last.
std::vector<std::size_t> avatar_key_frames(std::size_t frames, std::size_t stride);

/// The page script's part for the clip: name, fps, per frame its time, pair counts and
/// marked faces, the first crossing and worst frames, the avatar's positions at its key
/// frames and each garment's positions and distances in every frame, all frames of a mesh
/// quantized together over their common bounding box (mesh_encoding.hpp).
/// @throw std::invalid_argument when a frame has not one posed mesh per garment with the
///        garment's vertex count, an avatar of the page avatar's vertex count, one distance
///        per vertex, or a marked face outside its garment.
nlohmann::ordered_json page_animation_scene(const ReportPageData& data);

/// The controls under the view: play/pause, the frame slider with a tick per crossing frame
/// (the first crossing and the worst frame marked apart), a button to the worst frame, one
/// back to the files' pose, and the line that gives the frame's time and pair counts.
std::string frame_slider_html(const PageAnimation& animation);

}  // namespace gr
