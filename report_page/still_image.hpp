#pragma once

#include <string>

#include "report_page/page_data.hpp"
#include "report_page/rgb_image.hpp"
#include "report_page/view_frame.hpp"

namespace gr {

/// Which still: the figure seen from the front or from its side (see ViewFrame).
enum class StillView { kFront, kSide };

/// Size and look of a still image.
struct StillOptions {
  int width = 720;               ///< pixels
  int height = 960;              ///< pixels
  int supersample = 2;           ///< samples per pixel along each axis, box-filtered down
  bool highlight_no_fit = true;  ///< no-fit faces striped, as the page starts
};

/// The orthographic camera of a still: maps page-frame points to pixels, fitted so the
/// avatar and every garment's last shape fill the image with a margin.
struct StillCamera {
  Vector3d right, up, toward_viewer;   ///< unit axes of the image, right-handed
  double scale = 1.0;                  ///< pixels per page unit
  Vector2d centre = Vector2d::Zero();  ///< image-plane coordinates of the image centre
  int width = 0, height = 0;

  /// Pixel coordinates (x right, y down, from the image's top-left corner; pixel (i, j)
  /// covers [i, i+1) × [j, j+1)) and depth (larger is nearer the viewer) of a point.
  Vector3d project(const Vector3d& point) const;
};

/// The camera of render_still for `view` at `width` × `height` pixels, using the frame
/// guess_view_frame gives for the avatar.
/// @pre width, height > 0.
StillCamera still_camera(const ReportPageData& data, StillView view, int width, int height);

/// Renders the avatar and the last shape of each garment (the output, when there are two)
/// without a browser: a z-buffer rasterizer, orthographic, lit from the viewer (two-sided
/// Lambert with ambient), garment corners coloured as garment_corner_colours with the no-fit
/// stripes over them, the avatar in kAvatarColour on kBackgroundColour.
/// @pre options.width, height, supersample > 0.
RgbImage render_still(const ReportPageData& data, StillView view, const StillOptions& options = {});

/// Writes the front and side stills as PNG files.
/// @throw OutputError when a file cannot be written.
void write_still_images(const ReportPageData& data, const std::string& front_path,
                        const std::string& side_path, const StillOptions& options = {});

}  // namespace gr
