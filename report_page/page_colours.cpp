#include "report_page/page_colours.hpp"

#include <algorithm>
#include <cmath>

namespace gr {

const std::array<HeatStop, 5>& heat_stops() {
  static const std::array<HeatStop, 5> stops{{{0.0, {165, 0, 38}},
                                              {0.25, {244, 109, 67}},
                                              {0.5, {254, 224, 144}},
                                              {0.75, {116, 173, 209}},
                                              {1.0, {49, 54, 149}}}};
  return stops;
}

const std::array<HeatStop, 5>& ease_stops() {
  static const std::array<HeatStop, 5> stops{{{0.0, {165, 0, 38}},
                                              {0.25, {253, 174, 97}},
                                              {0.5, {26, 152, 80}},
                                              {0.75, {107, 174, 214}},
                                              {1.0, {8, 69, 148}}}};
  return stops;
}

Rgb8 heat_colour(double t) {
  const auto& stops = heat_stops();
  if (!(t < 1.0)) return stops.back().colour;
  t = std::max(t, 0.0);
  std::size_t i = 1;
  while (stops[i].position < t) ++i;
  const HeatStop& lo = stops[i - 1];
  const HeatStop& hi = stops[i];
  const double w = (t - lo.position) / (hi.position - lo.position);
  auto mix = [w](std::uint8_t a, std::uint8_t b) {
    return static_cast<std::uint8_t>(std::lround((1.0 - w) * a + w * b));
  };
  return {mix(lo.colour.r, hi.colour.r), mix(lo.colour.g, hi.colour.g),
          mix(lo.colour.b, hi.colour.b)};
}

double default_heat_range(const TriangleMesh& avatar) {
  const Vector3d extent =
      avatar.vertices.colwise().maxCoeff() - avatar.vertices.colwise().minCoeff();
  const double side = extent.maxCoeff();
  // A single point has no size: any positive range draws it.
  return side > 0.0 ? 0.01 * side : 1.0;
}

double page_heat_range(const ReportPageData& data) {
  return data.heat_range > 0.0 ? data.heat_range : default_heat_range(data.avatar);
}

bool on_no_fit_stripe(double x, double y) {
  return std::fmod(x + y, kNoFitStripePeriod) < kNoFitStripeWidth;
}

std::vector<Rgb8> garment_corner_colours(const PageGarment& garment, const GarmentShape& shape,
                                         double heat_range) {
  const auto face_count = static_cast<std::size_t>(garment.faces.rows());
  std::vector<bool> marked(face_count, false);
  for (const int f : shape.marked_faces) marked[static_cast<std::size_t>(f)] = true;
  std::vector<Rgb8> colours(3 * face_count);
  for (std::size_t f = 0; f < face_count; ++f)
    for (std::size_t k = 0; k < 3; ++k) {
      Rgb8& c = colours[3 * f + k];
      if (marked[f])
        c = kMarkedColour;
      else
        c = heat_colour(shape.distance[static_cast<std::size_t>(garment.faces(
                            static_cast<Eigen::Index>(f), static_cast<Eigen::Index>(k)))] /
                        heat_range);
    }
  return colours;
}

nlohmann::json page_colours_json() {
  auto rgb = [](const Rgb8& c) { return nlohmann::json::array({c.r, c.g, c.b}); };
  nlohmann::json stops = nlohmann::json::array();
  for (const HeatStop& s : heat_stops()) stops.push_back({s.position, rgb(s.colour)});
  nlohmann::json ease = nlohmann::json::array();
  for (const HeatStop& s : ease_stops()) ease.push_back({s.position, rgb(s.colour)});
  return {{"heat_stops", stops},
          {"ease_stops", ease},
          {"ease_unmeasured", rgb(kUnmeasuredEaseColour)},
          {"no_fit", rgb(kNoFitColour)},
          {"no_fit_stripes", {{"period", kNoFitStripePeriod}, {"width", kNoFitStripeWidth}}},
          {"marked", rgb(kMarkedColour)},
          {"avatar", rgb(kAvatarColour)},
          {"background", rgb(kBackgroundColour)}};
}

}  // namespace gr
