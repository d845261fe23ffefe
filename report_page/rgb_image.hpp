#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "report_page/page_colours.hpp"

namespace gr {

/// An 8-bit sRGB image, rows top to bottom, 3 bytes per pixel.
struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;  ///< 3 · width · height

  RgbImage() = default;
  /// A width × height image filled with `fill`. @pre width, height >= 0.
  RgbImage(int width, int height, Rgb8 fill);
  /// @pre 0 <= x < width, 0 <= y < height.
  Rgb8 at(int x, int y) const;
  void set(int x, int y, Rgb8 colour);
};

/// The image as a PNG file's bytes (libpng, 8-bit RGB).
/// @throw OutputError when libpng cannot encode it (e.g. an empty image).
std::string encode_png(const RgbImage& image);

/// Writes the image as a PNG file, atomically.
/// @throw OutputError when it cannot be encoded or written.
void write_png(const std::string& path, const RgbImage& image);

/// Reads a PNG file (any of libpng's formats) as 8-bit sRGB.
/// @throw InputError when the file is missing or not a PNG libpng can read.
RgbImage read_png(const std::string& path);

}  // namespace gr
