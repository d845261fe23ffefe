#include "report_page/view_frame.hpp"

#include <algorithm>
#include <array>

namespace gr {

ViewFrame guess_view_frame(const Eigen::Ref<const MatrixX3d>& points) {
  if (points.rows() == 0) return {};
  const Vector3d extent = (points.colwise().maxCoeff() - points.colwise().minCoeff()).transpose();
  std::array<int, 3> axes{0, 1, 2};
  // Largest extent first; stable, so ties keep x, y, z.
  std::stable_sort(axes.begin(), axes.end(), [&](int a, int b) { return extent[a] > extent[b]; });
  ViewFrame frame;
  frame.up = Vector3d::Unit(axes[0]);
  frame.side = Vector3d::Unit(axes[1]);
  frame.front = frame.side.cross(frame.up);
  return frame;
}

nlohmann::json to_json(const ViewFrame& frame) {
  auto axis = [](const Vector3d& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); };
  return {{"up", axis(frame.up)}, {"front", axis(frame.front)}, {"side", axis(frame.side)}};
}

}  // namespace gr
