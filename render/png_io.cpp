#include "render/png_io.hpp"

#include <png.h>

#include <fstream>
#include <stdexcept>
#include <string>

namespace gearsph::render {

// libpng's "simplified API" (libpng >= 1.6.22) reports errors through
// png_image::message instead of longjmp, so no setjmp meets C++ objects here.

RgbImage::RgbImage(int w, int h, Rgb8 fill) : width(w), height(h) {
  if (w <= 0 || h <= 0) throw std::invalid_argument("RgbImage: size must be positive");
  rgb.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3);
  for (std::size_t i = 0; i < rgb.size(); i += 3) {
    rgb[i] = fill.r;
    rgb[i + 1] = fill.g;
    rgb[i + 2] = fill.b;
  }
}

Rgb8 RgbImage::at(int x, int y) const {
  const std::size_t i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                         static_cast<std::size_t>(x)) *
                        3;
  return {rgb[i], rgb[i + 1], rgb[i + 2]};
}

void RgbImage::set(int x, int y, Rgb8 c) {
  const std::size_t i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                         static_cast<std::size_t>(x)) *
                        3;
  rgb[i] = c.r;
  rgb[i + 1] = c.g;
  rgb[i + 2] = c.b;
}

std::vector<unsigned char> encode_png(const RgbImage& image) {
  png_image desc{};
  desc.version = PNG_IMAGE_VERSION;
  desc.width = static_cast<png_uint_32>(image.width);
  desc.height = static_cast<png_uint_32>(image.height);
  desc.format = PNG_FORMAT_RGB;
  png_alloc_size_t size = 0;
  // First call measures, second call writes (libpng manual, "simplified API").
  if (!png_image_write_to_memory(&desc, nullptr, &size, 0, image.rgb.data(), 0, nullptr))
    throw std::runtime_error(std::string("PNG encoding failed: ") + desc.message);
  std::vector<unsigned char> bytes(size);
  if (!png_image_write_to_memory(&desc, bytes.data(), &size, 0, image.rgb.data(), 0, nullptr))
    throw std::runtime_error(std::string("PNG encoding failed: ") + desc.message);
  bytes.resize(size);
  return bytes;
}

RgbImage decode_png(std::span<const unsigned char> bytes) {
  png_image desc{};
  desc.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&desc, bytes.data(), bytes.size()))
    throw std::runtime_error(std::string("not a PNG: ") + desc.message);
  desc.format = PNG_FORMAT_RGB;
  RgbImage image(static_cast<int>(desc.width), static_cast<int>(desc.height));
  // White background for images with alpha, matching what a viewer shows.
  png_color background{255, 255, 255};
  if (!png_image_finish_read(&desc, &background, image.rgb.data(), 0, nullptr)) {
    png_image_free(&desc);
    throw std::runtime_error(std::string("PNG decoding failed: ") + desc.message);
  }
  return image;
}

void write_png(const std::filesystem::path& path, std::span<const unsigned char> bytes) {
  std::filesystem::path tmp = path;
  tmp += ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("cannot open " + tmp.string() + " for writing");
    out.write(reinterpret_cast<const char*>(bytes.data()),
              static_cast<std::streamsize>(bytes.size()));
    if (!out) throw std::runtime_error("cannot write " + tmp.string());
  }
  std::filesystem::rename(tmp, path);
}

}  // namespace gearsph::render
