#pragma once

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
};

}  // namespace gr
