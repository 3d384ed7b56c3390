#include "render/font.hpp"

#include <ft2build.h>
#include FT_FREETYPE_H

#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>

namespace gearsph::render {
namespace {

// Debian package fonts-dejavu-core.
constexpr const char* kFontPaths[2] = {"/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
                                       "/usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf"};

struct Glyph {
  int left = 0, top = 0;  // bitmap offset from the pen position (top is up)
  int width = 0, rows = 0;
  long advance = 0;  // 26.6 fixed point
  std::vector<std::uint8_t> coverage;
};

// One FT_Library with its two faces and a glyph cache, per thread.
class FontCache {
 public:
  FontCache() {
    if (FT_Init_FreeType(&library_) != 0) throw std::runtime_error("FreeType init failed");
    for (int k = 0; k < 2; ++k) {
      if (FT_New_Face(library_, kFontPaths[k], 0, &faces_[k]) != 0) {
        FT_Done_FreeType(library_);
        throw std::runtime_error(std::string("cannot load font ") + kFontPaths[k] +
                                 " (Debian package fonts-dejavu-core)");
      }
    }
  }
  ~FontCache() { FT_Done_FreeType(library_); }  // also frees the faces
  FontCache(const FontCache&) = delete;
  FontCache& operator=(const FontCache&) = delete;

  FT_Face face(const TextStyle& style) {
    FT_Face f = faces_[style.bold ? 1 : 0];
    FT_Set_Char_Size(f, 0, size_26_6(style), 72, 72);  // 72 dpi: points == pixels
    return f;
  }

  const Glyph& glyph(const TextStyle& style, char32_t code) {
    const auto key = std::make_tuple(style.bold, size_26_6(style), code);
    auto it = glyphs_.find(key);
    if (it == glyphs_.end()) it = glyphs_.emplace(key, render_glyph(face(style), code)).first;
    return it->second;
  }

  static long size_26_6(const TextStyle& style) { return std::lround(style.size_px * 64.0); }

 private:
  static Glyph render_glyph(FT_Face f, char32_t code) {
    Glyph g;
    if (FT_Load_Char(f, code, FT_LOAD_RENDER) != 0) return g;  // missing glyph: blank
    const FT_GlyphSlot slot = f->glyph;
    g.left = slot->bitmap_left;
    g.top = slot->bitmap_top;
    g.width = static_cast<int>(slot->bitmap.width);
    g.rows = static_cast<int>(slot->bitmap.rows);
    g.advance = slot->advance.x;
    g.coverage.resize(static_cast<std::size_t>(g.width) * static_cast<std::size_t>(g.rows));
    for (int r = 0; r < g.rows; ++r)
      for (int c = 0; c < g.width; ++c)
        g.coverage[static_cast<std::size_t>(r * g.width + c)] =
            slot->bitmap.buffer[r * slot->bitmap.pitch + c];
    return g;
  }

  FT_Library library_ = nullptr;
  FT_Face faces_[2] = {nullptr, nullptr};
  std::map<std::tuple<bool, long, char32_t>, Glyph> glyphs_;
};

FontCache& cache() {
  thread_local FontCache instance;
  return instance;
}

struct PlacedGlyph {
  const Glyph* glyph;
  int pen_x;  // whole pixels from the string origin
};

// Pen positions in 26.6 with pair kerning, rounded per glyph so the result
// does not depend on where the string is drawn.
std::vector<PlacedGlyph> layout(std::string_view utf8, const TextStyle& style, int& width) {
  FontCache& fc = cache();
  const FT_Face f = fc.face(style);
  std::vector<PlacedGlyph> placed;
  long pen = 0;
  FT_UInt previous = 0;
  for (char32_t code : decode_utf8(utf8)) {
    const FT_UInt index = FT_Get_Char_Index(f, code);
    if (previous != 0 && index != 0 && FT_HAS_KERNING(f)) {
      FT_Vector delta{};
      FT_Get_Kerning(f, previous, index, FT_KERNING_DEFAULT, &delta);
      pen += delta.x;
    }
    const Glyph& g = fc.glyph(style, code);
    placed.push_back({&g, static_cast<int>((pen + 32) >> 6)});
    pen += g.advance;
    previous = index;
  }
  width = static_cast<int>((pen + 32) >> 6);
  return placed;
}

std::uint8_t blend(std::uint8_t dst, std::uint8_t src, int alpha) {
  return static_cast<std::uint8_t>((dst * (255 - alpha) + src * alpha + 127) / 255);
}

void blend_pixel(RgbImage& image, int x, int y, Rgb8 colour, int alpha) {
  if (alpha == 0 || !image.contains(x, y)) return;
  const Rgb8 d = image.at(x, y);
  image.set(
      x, y,
      {blend(d.r, colour.r, alpha), blend(d.g, colour.g, alpha), blend(d.b, colour.b, alpha)});
}

}  // namespace

std::vector<char32_t> decode_utf8(std::string_view utf8) {
  std::vector<char32_t> out;
  for (std::size_t i = 0; i < utf8.size();) {
    const auto lead = static_cast<unsigned char>(utf8[i]);
    const int extra = lead < 0x80           ? 0
                      : (lead >> 5) == 0x6  ? 1
                      : (lead >> 4) == 0xE  ? 2
                      : (lead >> 3) == 0x1E ? 3
                                            : -1;
    if (extra < 0 || i + static_cast<std::size_t>(extra) >= utf8.size()) {
      out.push_back(0xFFFD);
      ++i;
      continue;
    }
    char32_t code = extra == 0 ? lead : lead & (0x3F >> extra);
    bool ok = true;
    for (int k = 1; k <= extra; ++k) {
      const auto next = static_cast<unsigned char>(utf8[i + static_cast<std::size_t>(k)]);
      ok = ok && (next >> 6) == 0x2;
      code = (code << 6) | (next & 0x3F);
    }
    out.push_back(ok ? code : 0xFFFD);
    i += ok ? static_cast<std::size_t>(extra) + 1 : 1;
  }
  return out;
}

TextMetrics measure_text(std::string_view utf8, const TextStyle& style) {
  TextMetrics m;
  layout(utf8, style, m.width);
  const FT_Face f = cache().face(style);
  m.ascent = static_cast<int>((f->size->metrics.ascender + 63) >> 6);
  m.descent = static_cast<int>((-f->size->metrics.descender + 63) >> 6);
  m.cap_height = cache().glyph(style, U'H').top;
  return m;
}

void draw_text(RgbImage& image, std::string_view utf8, int x, int y, const TextStyle& style,
               HAlign halign, VAlign valign, bool rotated) {
  const TextMetrics m = measure_text(utf8, style);
  int width = 0;
  const auto placed = layout(utf8, style, width);
  // Anchor in text coordinates: u along the baseline, v down from it.
  const int anchor_u = halign == HAlign::Left ? 0 : halign == HAlign::Centre ? width / 2 : width;
  const int anchor_v = valign == VAlign::Top      ? -m.ascent
                       : valign == VAlign::Middle ? -m.cap_height / 2
                       : valign == VAlign::Bottom ? m.descent
                                                  : 0;
  for (const PlacedGlyph& p : placed) {
    const Glyph& g = *p.glyph;
    for (int r = 0; r < g.rows; ++r) {
      for (int c = 0; c < g.width; ++c) {
        const int du = p.pen_x + g.left + c - anchor_u;
        const int dv = r - g.top - anchor_v;
        const int alpha = g.coverage[static_cast<std::size_t>(r * g.width + c)];
        // Counter-clockwise quarter turn: along-text goes up, "down" goes
        // right; the pixel square [du, du+1) lands on rows (-du-1, -du].
        if (rotated)
          blend_pixel(image, x + dv, y - du - 1, style.colour, alpha);
        else
          blend_pixel(image, x + du, y + dv, style.colour, alpha);
      }
    }
  }
}

}  // namespace gearsph::render
