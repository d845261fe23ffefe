#include "report_page/page_animation.hpp"

#include <algorithm>
#include <stdexcept>

#include <fmt/format.h>

#include "report_page/mesh_encoding.hpp"
#include "report_page/page_colours.hpp"
#include "report_page/page_html.hpp"

namespace gr {

namespace {

using Json = nlohmann::ordered_json;

/// Bytes of one vertex's position on the page before base64: three 16-bit coordinates.
constexpr std::size_t kPositionBytes = 6;

void require(bool condition, const std::string& what) {
  if (!condition) throw std::invalid_argument("report page animation: " + what);
}

/// `meshes` one under the other: #frames·#V×3.
MatrixX3d stacked(const std::vector<const MatrixX3d*>& meshes) {
  Eigen::Index rows = 0;
  for (const MatrixX3d* m : meshes) rows += m->rows();
  MatrixX3d out(rows, 3);
  Eigen::Index row = 0;
  for (const MatrixX3d* m : meshes) {
    out.middleRows(row, m->rows()) = *m;
    row += m->rows();
  }
  return out;
}

/// Where frame `f` sits along the slider's track, in percent.
double track_percent(std::size_t f, std::size_t frames) {
  return frames > 1 ? 100.0 * static_cast<double>(f) / static_cast<double>(frames - 1) : 0.0;
}

}  // namespace

std::vector<std::size_t> avatar_key_frames(std::size_t frames, std::size_t stride) {
  std::vector<std::size_t> keys;
  for (std::size_t f = 0; f < frames; f += std::max<std::size_t>(stride, 1)) keys.push_back(f);
  if (frames > 0 && keys.back() != frames - 1) keys.push_back(frames - 1);
  return keys;
}

std::size_t avatar_frame_stride(std::size_t frames, std::size_t avatar_vertices,
                                std::size_t garment_vertices) {
  const std::size_t frame_bytes = avatar_vertices * kPositionBytes;
  const std::size_t garment_bytes = frames * garment_vertices * kPositionBytes;
  const std::size_t room = std::max(
      kAnimationPositionBytes > garment_bytes ? kAnimationPositionBytes - garment_bytes : 0,
      kAnimationPositionBytes / 4);
  std::size_t stride = 1;
  while (stride + 1 < frames && avatar_key_frames(frames, stride).size() * frame_bytes > room)
    ++stride;
  return stride;
}

Json page_animation_scene(const ReportPageData& data) {
  const PageAnimation& animation = *data.animation;
  const std::size_t frame_count = animation.frames.size();
  require(frame_count > 0, "the clip has no frame");
  for (const std::optional<std::size_t>& marked : {animation.first_crossing, animation.worst_frame})
    require(!marked || *marked < frame_count, "a marked frame lies past the clip's end");
  const std::size_t garments = data.garments.size();
  const Eigen::Index avatar_vertices = data.avatar.vertices.rows();
  std::size_t garment_vertices = 0;
  for (const PageGarment& g : data.garments)
    garment_vertices += static_cast<std::size_t>(g.shapes.front().vertices.rows());

  Json times = Json::array(), avatar_pairs = Json::array(), self_pairs = Json::array(),
       layer_pairs = Json::array();
  for (std::size_t f = 0; f < frame_count; ++f) {
    const PageFrame& frame = animation.frames[f];
    const std::string which = fmt::format("frame {}", f);
    require(frame.avatar.rows() == avatar_vertices, which + ": the avatar's vertex count differs");
    require(frame.garments.size() == garments && frame.distance.size() == garments &&
                frame.marked_faces.size() == garments,
            which + ": not one posed mesh, distance list and mark list per garment");
    for (std::size_t g = 0; g < garments; ++g) {
      const Eigen::Index n = data.garments[g].shapes.front().vertices.rows();
      require(
          frame.garments[g].rows() == n && static_cast<Eigen::Index>(frame.distance[g].size()) == n,
          which + ": garment '" + data.garments[g].name + "' has another vertex count");
      for (const int face : frame.marked_faces[g])
        require(face >= 0 && face < data.garments[g].faces.rows(),
                which + ": a marked face outside garment '" + data.garments[g].name + "'");
    }
    times.push_back(frame.time);
    avatar_pairs.push_back(frame.avatar_pairs);
    self_pairs.push_back(frame.self_pairs);
    layer_pairs.push_back(frame.layer_pairs);
  }

  const std::vector<std::size_t> keys = avatar_key_frames(
      frame_count, avatar_frame_stride(frame_count, static_cast<std::size_t>(avatar_vertices),
                                       garment_vertices));
  std::vector<const MatrixX3d*> avatar_frames;
  for (const std::size_t f : keys) avatar_frames.push_back(&animation.frames[f].avatar);

  Json garment_entries = Json::array();
  for (std::size_t g = 0; g < garments; ++g) {
    std::vector<const MatrixX3d*> positions;
    std::vector<double> distance;
    Json marked = Json::array();
    for (const PageFrame& frame : animation.frames) {
      positions.push_back(&frame.garments[g]);
      distance.insert(distance.end(), frame.distance[g].begin(), frame.distance[g].end());
      marked.push_back(frame.marked_faces[g]);
    }
    garment_entries.push_back({{"positions", encode_positions(stacked(positions))},
                               {"distance", encode_unit_values(distance)},
                               {"marked", std::move(marked)}});
  }
  const auto index_or_null = [](std::optional<std::size_t> f) -> Json {
    return f ? Json(*f) : Json(nullptr);
  };
  return Json{
      {"clip", animation.clip},
      {"fps", animation.fps},
      {"clip_count", animation.clip_count},
      {"frame_count", frame_count},
      {"times", std::move(times)},
      {"avatar_pairs", std::move(avatar_pairs)},
      {"self_pairs", std::move(self_pairs)},
      {"layer_pairs", std::move(layer_pairs)},
      {"first_crossing", index_or_null(animation.first_crossing)},
      {"worst_frame", index_or_null(animation.worst_frame)},
      {"avatar", {{"frames", keys}, {"positions", encode_positions(stacked(avatar_frames))}}},
      {"garments", std::move(garment_entries)}};
}

std::string frame_slider_html(const PageAnimation& animation) {
  const std::size_t frames = animation.frames.size();
  const std::optional<std::size_t> first = animation.first_crossing;
  const std::optional<std::size_t> worst = animation.worst_frame;
  std::string marks;
  for (std::size_t f = 0; f < frames; ++f) {
    if (animation.frames[f].total_pairs() == 0) continue;
    std::string kind = "cross";
    std::string id;
    if (f == worst) {
      kind += " worst";
      id = " id=\"gr-mark-worst\"";
    }
    if (f == first) {
      kind += " first";
      id = f == worst ? id : " id=\"gr-mark-first\"";
    }
    marks += fmt::format("<i class=\"mark {}\"{} data-frame=\"{}\" style=\"left: {:.3f}%\"></i>",
                         kind, id, f, track_percent(f, frames));
  }
  std::string out = "<div class=\"player\" id=\"gr-player\">\n";
  out += "<button type=\"button\" id=\"gr-play\">play</button>\n";
  out += fmt::format(
      "<div class=\"frame-track\"><input type=\"range\" id=\"gr-frame\" min=\"0\" max=\"{}\" "
      "step=\"1\" value=\"0\" aria-label=\"frame of clip {}\"><div class=\"frame-marks\" "
      "aria-hidden=\"true\" style=\"--marked: rgb({},{},{})\">{}</div></div>\n",
      frames - 1, html_escape(animation.clip), kMarkedColour.r, kMarkedColour.g, kMarkedColour.b,
      marks);
  if (worst)
    out += fmt::format(
        "<button type=\"button\" id=\"gr-worst\" data-frame=\"{}\">worst frame ({}, {} pairs)"
        "</button>\n",
        *worst, *worst, animation.frames[*worst].total_pairs());
  out += "<button type=\"button\" id=\"gr-rest\">pose as given</button>\n";
  out += "<span class=\"frame-info\" id=\"gr-frame-info\">pose as given</span>\n</div>\n";
  const std::string marks_text =
      first
          ? fmt::format("Ticks: frames that cross; outlined: the first ({}); tall: the worst ({}).",
                        *first, *worst)
          : "No frame crosses.";
  out += fmt::format(
      "<p class=\"hint\">Clip “{}”{}: {} frames at {:g} fps. {} Space plays and pauses, arrow "
      "keys step.</p>\n",
      html_escape(animation.clip),
      animation.clip_count > 1
          ? fmt::format(" (of {} clips checked, the one with the most crossing frames)",
                        animation.clip_count)
          : "",
      frames, animation.fps, marks_text);
  return out;
}

}  // namespace gr
