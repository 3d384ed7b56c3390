#pragma once
// An 8-bit sRGB raster and its PNG encoding (libpng). The encoder writes no
// time or text chunks, so the same pixels always give the same bytes.
#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

namespace gearsph::render {

struct Rgb8 {
  std::uint8_t r = 0, g = 0, b = 0;
  friend bool operator==(const Rgb8&, const Rgb8&) = default;
};

// Row-major RGB, top row first (PNG order).
struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;

  RgbImage() = default;
  RgbImage(int w, int h, Rgb8 fill = {255, 255, 255});
  bool contains(int x, int y) const { return x >= 0 && y >= 0 && x < width && y < height; }
  Rgb8 at(int x, int y) const;
  void set(int x, int y, Rgb8 c);
};

std::vector<unsigned char> encode_png(const RgbImage& image);
// Throws std::runtime_error on anything that is not a valid PNG. Any PNG
// colour type is converted to 8-bit RGB (alpha dropped, grey expanded).
RgbImage decode_png(std::span<const unsigned char> bytes);

// Writes atomically enough for a reader polling the directory: a temporary
// file in the same directory, then a rename. Throws on I/O errors.
void write_png(const std::filesystem::path& path, std::span<const unsigned char> bytes);

}  // namespace gearsph::render
