#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "report_page/page_data.hpp"

namespace gr {

/// An sRGB colour, 8 bits per channel.
struct Rgb8 {
  std::uint8_t r = 0, g = 0, b = 0;
  bool operator==(const Rgb8& o) const { return r == o.r && g == o.g && b == o.b; }
  bool operator!=(const Rgb8& o) const { return !(*this == o); }
};

/// One stop of the distance heat map: at `position` (0 on the body, 1 at the heat range)
/// the colour is `colour`; between stops it is interpolated linearly in sRGB.
struct HeatStop {
  double position;
  Rgb8 colour;
};

/// The heat map, red on the body through yellow to blue at the heat range and beyond
/// (ColorBrewer's RdYlBu): no stop is grey, so avatar and garment never look alike.
const std::array<HeatStop, 5>& heat_stops();

/// The heat map's colour at `t` (clamped to [0, 1]; NaN counts as 1).
Rgb8 heat_colour(double t);

/// The ease map, over ratio / 2 (the ease kept: 0 painted onto the body, 0.5 all of it,
/// 1 twice it and more): red through orange to green at the source ease, then blue where
/// the garment stands further off (ColorBrewer's RdYlGn and Blues).
const std::array<HeatStop, 5>& ease_stops();
/// Vertices whose ease was not measured (no-fit, or no source ease there).
constexpr Rgb8 kUnmeasuredEaseColour{222, 210, 180};

/// Faces listed as no-fit are striped in this colour over their heat colour, so their
/// distance to the body stays readable.
constexpr Rgb8 kNoFitColour{96, 178, 96};
/// The stripes run diagonally across the screen: `kNoFitStripeWidth` pixels of every
/// `kNoFitStripePeriod` (in output pixels, along x + y).
constexpr double kNoFitStripePeriod = 10.0;
constexpr double kNoFitStripeWidth = 4.0;

/// Whether the point (x, y) of the screen, in output pixels, lies on a no-fit stripe.
bool on_no_fit_stripe(double x, double y);
/// Intersecting or otherwise marked faces: a colour outside the heat map.
constexpr Rgb8 kMarkedColour{230, 0, 230};
constexpr Rgb8 kAvatarColour{170, 170, 170};
constexpr Rgb8 kBackgroundColour{244, 244, 246};

/// The default heat range: 1% of the avatar's largest bounding-box side (1.7 cm on a body
/// 1.7 m tall), in the avatar's units. A fitted garment rests within a few tenths of that,
/// so fitted parts read red and loose parts shade toward blue.
/// @pre avatar has at least one vertex.
double default_heat_range(const TriangleMesh& avatar);

/// The heat range a page uses: data.heat_range when positive, else the default.
double page_heat_range(const ReportPageData& data);

/// The colour of every face corner of one shape of a garment (#F×3 entries, face-major):
/// marked faces in kMarkedColour, the others the heat colour of the corner vertex's
/// distance / heat_range (no-fit stripes go on top when drawn). The page's script applies
/// the same rule to the stops and colours of page_colours_json.
/// @pre shape belongs to garment (distance has one entry per vertex); heat_range > 0.
std::vector<Rgb8> garment_corner_colours(const PageGarment& garment, const GarmentShape& shape,
                                         double heat_range);

/// The stops, colours and stripes above, as the page's script reads them.
nlohmann::json page_colours_json();

}  // namespace gr
