#include "report_page/rgb_image.hpp"

#include <png.h>

#include "core/common/errors.hpp"
#include "core/io/atomic_file.hpp"

namespace gr {

RgbImage::RgbImage(int w, int h, Rgb8 fill)
    : width(w), height(h), pixels(3 * static_cast<std::size_t>(w) * static_cast<std::size_t>(h)) {
  for (std::size_t i = 0; i < pixels.size(); i += 3) {
    pixels[i] = fill.r;
    pixels[i + 1] = fill.g;
    pixels[i + 2] = fill.b;
  }
}

Rgb8 RgbImage::at(int x, int y) const {
  const std::size_t i = 3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                             static_cast<std::size_t>(x));
  return {pixels[i], pixels[i + 1], pixels[i + 2]};
}

void RgbImage::set(int x, int y, Rgb8 colour) {
  const std::size_t i = 3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                             static_cast<std::size_t>(x));
  pixels[i] = colour.r;
  pixels[i + 1] = colour.g;
  pixels[i + 2] = colour.b;
}

std::string encode_png(const RgbImage& image) {
  png_image header{};
  header.version = PNG_IMAGE_VERSION;
  header.width = static_cast<png_uint_32>(image.width);
  header.height = static_cast<png_uint_32>(image.height);
  header.format = PNG_FORMAT_RGB;
  png_alloc_size_t size = 0;
  // The first call sizes the buffer, the second fills it.
  if (image.width <= 0 || image.height <= 0 ||
      !png_image_write_to_memory(&header, nullptr, &size, 0, image.pixels.data(), 0, nullptr))
    throw OutputError(std::string("cannot encode a PNG image: ") +
                      (header.message[0] ? header.message : "empty image"));
  std::string bytes(size, '\0');
  if (!png_image_write_to_memory(&header, bytes.data(), &size, 0, image.pixels.data(), 0, nullptr))
    throw OutputError(std::string("cannot encode a PNG image: ") + header.message);
  bytes.resize(size);
  return bytes;
}

void write_png(const std::string& path, const RgbImage& image) {
  const std::string bytes = encode_png(image);
  write_file_atomically(path, [&](std::ostream& out) {
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  });
}

RgbImage read_png(const std::string& path) {
  png_image header{};
  header.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&header, path.c_str()))
    throw InputError(path, 0, std::string("not a readable PNG file: ") + header.message);
  header.format = PNG_FORMAT_RGB;
  RgbImage image(static_cast<int>(header.width), static_cast<int>(header.height), Rgb8{});
  if (!png_image_finish_read(&header, nullptr, image.pixels.data(), 0, nullptr)) {
    png_image_free(&header);
    throw InputError(path, 0, std::string("cannot decode the PNG file: ") + header.message);
  }
  return image;
}

}  // namespace gr
