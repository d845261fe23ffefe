#pragma once

#include <nlohmann/json.hpp>

#include "core/common/types.hpp"

namespace gr {

/// The axes a figure is viewed along, unit vectors of the page's frame, right-handed:
/// front = side × up. The front view looks at the figure from +front with +up up and
/// +side to the right; the side view looks from +side.
struct ViewFrame {
  Vector3d up = Vector3d::UnitY();
  Vector3d front = Vector3d::UnitZ();
  Vector3d side = Vector3d::UnitX();
};

/// Guesses the frame of a standing figure from its points (#P×3): up is the coordinate
/// axis of largest extent (a body is taller than wide), side the wider of the other two
/// (shoulders are wider than the chest is deep). That puts a Y-up figure's front at +Z
/// and a Z-up one's at -Y, the usual conventions of Y-up and Z-up tools. Ties keep the
/// axis order x, y, z; no points gives the Y-up frame.
ViewFrame guess_view_frame(const Eigen::Ref<const MatrixX3d>& points);

/// {"up": [x, y, z], "front": [...], "side": [...]}.
nlohmann::json to_json(const ViewFrame& frame);

}  // namespace gr
