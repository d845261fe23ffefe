#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/common/types.hpp"

namespace gr {

/// One shape of a garment on the page, e.g. the input as placed or the refitted output.
/// Lengths and positions are in the page's frame (the avatar file's frame and units).
struct GarmentShape {
  std::string label;             ///< shown on the toggle ("input", "output")
  MatrixX3d vertices;            ///< #V×3
  std::vector<double> distance;  ///< #V: unsigned distance from each vertex to the avatar surface
  std::vector<int>
      marked_faces;  ///< faces to highlight: intersecting, degenerate or otherwise flagged
  /// #V: the ease kept (EaseMeasure::ratio: 1 kept, 0 painted on), NaN where not measured;
  /// empty when the page has no ease to show.
  std::vector<double> ease_ratio{};
};

/// A garment on the page. Its shapes share the faces; with two shapes the page toggles
/// between them.
struct PageGarment {
  std::string name;
  MatrixX3i faces;                   ///< #F×3, indices into each shape's vertices
  std::vector<bool> no_fit;          ///< #F (true: the face hangs free), or empty for none
  std::vector<GarmentShape> shapes;  ///< one or two
};

/// One sampled frame of a clip: the avatar and the garments posed, and what crossed.
/// Positions and lengths in the page's frame and units.
struct PageFrame {
  double time = 0.0;                ///< seconds from the clip's first keyframe
  std::size_t avatar_pairs = 0;     ///< garment–avatar face pairs crossing
  std::size_t self_pairs = 0;       ///< garment self pairs crossing (not crossing at rest)
  std::size_t layer_pairs = 0;      ///< garment–garment pairs crossing (not crossing at rest)
  MatrixX3d avatar;                 ///< #Va×3, the avatar posed
  std::vector<MatrixX3d> garments;  ///< per page garment, #Vg×3, posed as played
  /// Per garment, #Vg: unsigned distance from each posed vertex to the posed avatar.
  std::vector<std::vector<double>> distance;
  std::vector<std::vector<int>> marked_faces;  ///< per garment, its faces in crossing pairs
  std::size_t total_pairs() const { return avatar_pairs + self_pairs + layer_pairs; }
};

/// A clip played on the page's avatar and garments, frame by frame (the frame slider).
struct PageAnimation {
  std::string clip;  ///< the clip's name
  double fps = 0.0;  ///< frames sampled per second
  /// Clips that were checked; the page plays `clip`, the report holds them all.
  std::size_t clip_count = 1;
  std::vector<PageFrame> frames;
  /// The first frame with a crossing pair, and the one with the most, as the check that
  /// counted the pairs names them; none when every frame is free.
  std::optional<std::size_t> first_crossing{};
  std::optional<std::size_t> worst_frame{};
};

/// Everything a report page shows: the avatar, the garments coloured by distance to it,
/// and the JSON documents whose numbers go beside the view.
struct ReportPageData {
  std::string title;
  std::string subtitle;  ///< one line under the title, e.g. the input files
  TriangleMesh avatar;   ///< #Va×3 / #Fa×3, the page's frame
  std::vector<PageGarment> garments;
  /// Distance at the cold end of the heat map (page units); farther is drawn in that colour.
  /// 0 selects default_heat_range(avatar).
  double heat_range = 0.0;
  std::string units = "avatar units";  ///< name of the page's length unit
  nlohmann::json report;               ///< a retarget run's report.json, or null
  nlohmann::ordered_json certificate;  ///< certificate.json or a validation report, or null
  /// A clip to play under the view with a frame slider; none: the page shows the files' pose.
  std::optional<PageAnimation> animation{};
};

}  // namespace gr
