#include "report_page/still_image.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gr {

namespace {

/// Light: a fraction from all around plus the rest from the viewer's direction.
constexpr double kAmbient = 0.35;
/// Blank border around the figure, as a fraction of the image's size.
constexpr double kMargin = 0.04;

/// Area-weighted vertex normals (#V×3, unit; zero where no face with area touches).
MatrixX3d vertex_normals(const Eigen::Ref<const MatrixX3d>& vertices,
                         const Eigen::Ref<const MatrixX3i>& faces) {
  MatrixX3d normals = MatrixX3d::Zero(vertices.rows(), 3);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Vector3d a = vertices.row(faces(f, 0)).transpose();
    const Vector3d b = vertices.row(faces(f, 1)).transpose();
    const Vector3d c = vertices.row(faces(f, 2)).transpose();
    const Vector3d n = (b - a).cross(c - a);
    for (int k = 0; k < 3; ++k) normals.row(faces(f, k)) += n.transpose();
  }
  for (Eigen::Index v = 0; v < normals.rows(); ++v) {
    const double length = normals.row(v).norm();
    if (length > 0.0) normals.row(v) /= length;
  }
  return normals;
}

Vector3d as_vector(Rgb8 c) { return Vector3d(c.r, c.g, c.b); }

/// A supersampled colour and depth buffer.
class Raster {
 public:
  /// `factor` samples per output pixel along each axis.
  Raster(int width, int height, int factor)
      : width_(width), height_(height), factor_(factor),
        colour_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height),
                Eigen::Vector3f(kBackgroundColour.r, kBackgroundColour.g, kBackgroundColour.b)),
        depth_(colour_.size(), -std::numeric_limits<double>::infinity()) {}

  /// Draws a triangle given its corners' pixel coordinates and depth (p), colours (0..255)
  /// and light factors, keeping the nearest surface at each sample; `striped` lays the
  /// no-fit stripes over it.
  void triangle(const std::array<Vector3d, 3>& p, const std::array<Vector3d, 3>& colour,
                const std::array<double, 3>& light, bool striped) {
    const double area = edge(p[0], p[1], p[2]);
    if (!(std::abs(area) > 0.0)) return;
    const int x0 =
        std::max(0, static_cast<int>(std::floor(std::min({p[0].x(), p[1].x(), p[2].x()}))));
    const int x1 =
        std::min(width_ - 1, static_cast<int>(std::ceil(std::max({p[0].x(), p[1].x(), p[2].x()}))));
    const int y0 =
        std::max(0, static_cast<int>(std::floor(std::min({p[0].y(), p[1].y(), p[2].y()}))));
    const int y1 = std::min(height_ - 1,
                            static_cast<int>(std::ceil(std::max({p[0].y(), p[1].y(), p[2].y()}))));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const Vector3d s(x + 0.5, y + 0.5, 0.0);
        const double w0 = edge(p[1], p[2], s) / area;
        const double w1 = edge(p[2], p[0], s) / area;
        const double w2 = 1.0 - w0 - w1;
        if (w0 < 0.0 || w1 < 0.0 || w2 < 0.0) continue;
        const double z = w0 * p[0].z() + w1 * p[1].z() + w2 * p[2].z();
        const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                              static_cast<std::size_t>(x);
        if (z <= depth_[i]) continue;
        depth_[i] = z;
        if (striped && on_no_fit_stripe(s.x() / factor_, s.y() / factor_))
          colour_[i] = ((w0 * light[0] + w1 * light[1] + w2 * light[2]) * as_vector(kNoFitColour))
                           .cast<float>();
        else
          colour_[i] = ((w0 * light[0]) * colour[0] + (w1 * light[1]) * colour[1] +
                        (w2 * light[2]) * colour[2])
                           .cast<float>();
      }
  }

  /// Box-filters factor × factor blocks of samples into one pixel each.
  RgbImage downsample() const {
    const int factor = factor_;
    RgbImage image(width_ / factor, height_ / factor, kBackgroundColour);
    const double samples = static_cast<double>(factor * factor);
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) {
        Vector3d sum = Vector3d::Zero();
        for (int dy = 0; dy < factor; ++dy)
          for (int dx = 0; dx < factor; ++dx)
            sum += colour_[static_cast<std::size_t>(y * factor + dy) *
                               static_cast<std::size_t>(width_) +
                           static_cast<std::size_t>(x * factor + dx)]
                       .cast<double>();
        const Vector3d c = (sum / samples).cwiseMax(0.0).cwiseMin(255.0);
        image.set(x, y,
                  {static_cast<std::uint8_t>(std::lround(c.x())),
                   static_cast<std::uint8_t>(std::lround(c.y())),
                   static_cast<std::uint8_t>(std::lround(c.z()))});
      }
    return image;
  }

 private:
  static double edge(const Vector3d& a, const Vector3d& b, const Vector3d& c) {
    return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
  }

  int width_, height_, factor_;
  // Floats: a supersampled still has millions of samples.
  std::vector<Eigen::Vector3f> colour_;
  std::vector<double> depth_;
};

/// Draws a mesh whose corner colours are given face-major (3 per face); faces flagged in
/// `striped` (#F, or empty for none) get the no-fit stripes.
void draw_mesh(Raster& raster, const StillCamera& camera,
               const Eigen::Ref<const MatrixX3d>& vertices,
               const Eigen::Ref<const MatrixX3i>& faces, const std::vector<Rgb8>& corner_colours,
               const std::vector<bool>& striped) {
  const MatrixX3d normals = vertex_normals(vertices, faces);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    std::array<Vector3d, 3> p, colour;
    std::array<double, 3> light{};
    for (int k = 0; k < 3; ++k) {
      const Eigen::Index v = faces(f, k);
      p[k] = camera.project(vertices.row(v).transpose());
      colour[k] = as_vector(corner_colours[static_cast<std::size_t>(3 * f + k)]);
      // Two-sided: garments are open surfaces seen from both sides.
      light[k] = kAmbient +
                 (1.0 - kAmbient) * std::abs(normals.row(v).dot(camera.toward_viewer.transpose()));
    }
    raster.triangle(p, colour, light, !striped.empty() && striped[static_cast<std::size_t>(f)]);
  }
}

}  // namespace

Vector3d StillCamera::project(const Vector3d& point) const {
  const double u = point.dot(right) - centre.x();
  const double v = point.dot(up) - centre.y();
  return Vector3d(0.5 * width + scale * u, 0.5 * height - scale * v, point.dot(toward_viewer));
}

StillCamera still_camera(const ReportPageData& data, StillView view, int width, int height) {
  const ViewFrame frame = guess_view_frame(data.avatar.vertices);
  StillCamera camera;
  camera.width = width;
  camera.height = height;
  camera.up = frame.up;
  camera.toward_viewer = view == StillView::kFront ? frame.front : frame.side;
  camera.right = camera.up.cross(camera.toward_viewer);
  Vector2d lo = Vector2d::Constant(std::numeric_limits<double>::infinity());
  Vector2d hi = -lo;
  auto include = [&](const Eigen::Ref<const MatrixX3d>& points) {
    for (Eigen::Index i = 0; i < points.rows(); ++i) {
      const Vector2d q(points.row(i).dot(camera.right.transpose()),
                       points.row(i).dot(camera.up.transpose()));
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
  };
  include(data.avatar.vertices);
  for (const PageGarment& garment : data.garments)
    if (!garment.shapes.empty()) include(garment.shapes.back().vertices);
  if (!(hi.x() >= lo.x())) return camera;  // nothing to see
  camera.centre = 0.5 * (lo + hi);
  const Vector2d extent = (hi - lo).cwiseMax(std::numeric_limits<double>::min());
  camera.scale = (1.0 - 2.0 * kMargin) * std::min(width / extent.x(), height / extent.y());
  return camera;
}

RgbImage render_still(const ReportPageData& data, StillView view, const StillOptions& options) {
  const int factor = options.supersample;
  Raster raster(options.width * factor, options.height * factor, factor);
  const StillCamera camera =
      still_camera(data, view, options.width * factor, options.height * factor);
  draw_mesh(
      raster, camera, data.avatar.vertices, data.avatar.faces,
      std::vector<Rgb8>(3 * static_cast<std::size_t>(data.avatar.faces.rows()), kAvatarColour), {});
  const double heat_range = page_heat_range(data);
  for (const PageGarment& garment : data.garments) {
    if (garment.shapes.empty()) continue;
    const GarmentShape& shape = garment.shapes.back();
    draw_mesh(raster, camera, shape.vertices, garment.faces,
              garment_corner_colours(garment, shape, heat_range),
              options.highlight_no_fit ? garment.no_fit : std::vector<bool>());
  }
  return raster.downsample();
}

void write_still_images(const ReportPageData& data, const std::string& front_path,
                        const std::string& side_path, const StillOptions& options) {
  write_png(front_path, render_still(data, StillView::kFront, options));
  write_png(side_path, render_still(data, StillView::kSide, options));
}

}  // namespace gr
