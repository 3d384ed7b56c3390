#include "render/gl_context.hpp"

#include <GL/osmesa.h>
// osmesa.h includes GL/gl.h (fixed-function GL 1.x entry points, exported by
// libOSMesa itself, loaded with it: gl() below).
#include <dlfcn.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "render/colormap.hpp"

namespace gearsph::render {
namespace {

// OSMesa (and the GL 1.x entry points it exports) loaded when the first
// picture is drawn, not when the program starts: it brings LLVM
// (llvmpipe), whose half a million relocations would slow the start of
// every process, drawing or not (docs/speed-accuracy-history.md, "Outputs"). The
// same library and functions as linking it.
struct OsMesaApi {
  decltype(&::OSMesaCreateContextAttribs) OSMesaCreateContextAttribs = nullptr;
  decltype(&::OSMesaDestroyContext) OSMesaDestroyContext = nullptr;
  decltype(&::OSMesaMakeCurrent) OSMesaMakeCurrent = nullptr;
  decltype(&::OSMesaPixelStore) OSMesaPixelStore = nullptr;
  decltype(&::glBindTexture) glBindTexture = nullptr;
  decltype(&::glClear) glClear = nullptr;
  decltype(&::glClearColor) glClearColor = nullptr;
  decltype(&::glColorPointer) glColorPointer = nullptr;
  decltype(&::glDeleteTextures) glDeleteTextures = nullptr;
  decltype(&::glDisable) glDisable = nullptr;
  decltype(&::glDisableClientState) glDisableClientState = nullptr;
  decltype(&::glDrawArrays) glDrawArrays = nullptr;
  decltype(&::glEnable) glEnable = nullptr;
  decltype(&::glEnableClientState) glEnableClientState = nullptr;
  decltype(&::glFinish) glFinish = nullptr;
  decltype(&::glGenTextures) glGenTextures = nullptr;
  decltype(&::glLoadIdentity) glLoadIdentity = nullptr;
  decltype(&::glMatrixMode) glMatrixMode = nullptr;
  decltype(&::glOrtho) glOrtho = nullptr;
  decltype(&::glPixelStorei) glPixelStorei = nullptr;
  decltype(&::glScissor) glScissor = nullptr;
  decltype(&::glShadeModel) glShadeModel = nullptr;
  decltype(&::glTexCoordPointer) glTexCoordPointer = nullptr;
  decltype(&::glTexEnvi) glTexEnvi = nullptr;
  decltype(&::glTexImage1D) glTexImage1D = nullptr;
  decltype(&::glTexParameteri) glTexParameteri = nullptr;
  decltype(&::glVertexPointer) glVertexPointer = nullptr;
  decltype(&::glViewport) glViewport = nullptr;
};

const OsMesaApi& gl() {
  static const OsMesaApi api = [] {
    void* lib = dlopen("libOSMesa.so.8", RTLD_NOW | RTLD_LOCAL);
    if (lib == nullptr) {
      throw std::runtime_error(std::string("OSMesa is not installed (Debian libosmesa6): ") +
                               dlerror());
    }
    OsMesaApi a;
    auto load = [lib](auto& fn, const char* name) {
      fn = reinterpret_cast<std::remove_reference_t<decltype(fn)>>(dlsym(lib, name));
      if (fn == nullptr) throw std::runtime_error(std::string("OSMesa lacks ") + name);
    };
    load(a.OSMesaCreateContextAttribs, "OSMesaCreateContextAttribs");
    load(a.OSMesaDestroyContext, "OSMesaDestroyContext");
    load(a.OSMesaMakeCurrent, "OSMesaMakeCurrent");
    load(a.OSMesaPixelStore, "OSMesaPixelStore");
    load(a.glBindTexture, "glBindTexture");
    load(a.glClear, "glClear");
    load(a.glClearColor, "glClearColor");
    load(a.glColorPointer, "glColorPointer");
    load(a.glDeleteTextures, "glDeleteTextures");
    load(a.glDisable, "glDisable");
    load(a.glDisableClientState, "glDisableClientState");
    load(a.glDrawArrays, "glDrawArrays");
    load(a.glEnable, "glEnable");
    load(a.glEnableClientState, "glEnableClientState");
    load(a.glFinish, "glFinish");
    load(a.glGenTextures, "glGenTextures");
    load(a.glLoadIdentity, "glLoadIdentity");
    load(a.glMatrixMode, "glMatrixMode");
    load(a.glOrtho, "glOrtho");
    load(a.glPixelStorei, "glPixelStorei");
    load(a.glScissor, "glScissor");
    load(a.glShadeModel, "glShadeModel");
    load(a.glTexCoordPointer, "glTexCoordPointer");
    load(a.glTexEnvi, "glTexEnvi");
    load(a.glTexImage1D, "glTexImage1D");
    load(a.glTexParameteri, "glTexParameteri");
    load(a.glVertexPointer, "glVertexPointer");
    load(a.glViewport, "glViewport");
    return a;  // the library stays loaded for the process's life
  }();
  return api;
}

// The per-thread context and the colour buffer it renders into.
//
// Mesa 22.3's OSMesa keeps the old framebuffer textures alive when a context
// is bound again at a different size (measured: RSS grows by width * height
// * 4 bytes per size change, without bound). A size change therefore gets a
// fresh context; same-size renders, the common case, reuse the context.
// What remains is a few hundred bytes OSMesa never frees per destroyed
// context (see tests/lsan.supp).
class GlContext {
 public:
  GlContext() { create(); }
  ~GlContext() { destroy(); }
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  void make_current(int width, int height) {
    if (bound_ && (width != width_ || height != height_)) {
      destroy();
      create();
    }
    buffer_.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4, 0);
    if (!gl().OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, width, height))
      throw std::runtime_error("OSMesa: cannot bind a " + std::to_string(width) + "x" +
                               std::to_string(height) + " buffer");
    gl().OSMesaPixelStore(OSMESA_Y_UP, 0);  // buffer row 0 = top row, as in PNG
    bound_ = true;
    width_ = width;
    height_ = height;
  }

  const std::uint8_t* pixels() const { return buffer_.data(); }

 private:
  void create() {
    // Creation touches Mesa's process-wide state (screen, LLVM set-up):
    // serialise it. Rendering itself runs in parallel.
    const std::lock_guard lock(creation_mutex());
    const int attributes[] = {OSMESA_FORMAT,
                              OSMESA_RGBA,
                              OSMESA_DEPTH_BITS,
                              0,
                              OSMESA_STENCIL_BITS,
                              0,
                              OSMESA_ACCUM_BITS,
                              0,
                              OSMESA_PROFILE,
                              OSMESA_COMPAT_PROFILE,
                              0};
    context_ = gl().OSMesaCreateContextAttribs(attributes, nullptr);
    if (context_ == nullptr) throw std::runtime_error("OSMesa: cannot create a GL context");
    bound_ = false;
  }
  void destroy() {
    const std::lock_guard lock(creation_mutex());
    gl().OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);  // release before destroying
    gl().OSMesaDestroyContext(context_);
    context_ = nullptr;
  }
  static std::mutex& creation_mutex() {
    static std::mutex m;
    return m;
  }

  OSMesaContext context_ = nullptr;
  bool bound_ = false;
  int width_ = 0, height_ = 0;
  std::vector<std::uint8_t> buffer_;
};

GlContext& thread_context() {
  thread_local GlContext context;
  return context;
}

thread_local bool canvas_active = false;

// OSMesa's largest drawable (OSMESA_MAX_WIDTH/HEIGHT on llvmpipe).
constexpr int kMaxBufferSide = 16384;

// sRGB byte -> linear light in 16 bits, and back with correct rounding.
// Identical samples average to exactly their own value, so flat areas keep
// their exact colour; edges are blended in linear light (no dark fringes).
const std::array<std::uint16_t, 256>& to_linear16() {
  static const auto table = [] {
    std::array<std::uint16_t, 256> t{};
    for (int i = 0; i < 256; ++i)
      t[static_cast<std::size_t>(i)] =
          static_cast<std::uint16_t>(std::lround(65535.0 * srgb_to_linear(i / 255.0)));
    return t;
  }();
  return table;
}

const std::vector<std::uint8_t>& to_srgb8() {
  static const auto table = [] {
    std::vector<std::uint8_t> t(65536);
    for (std::size_t i = 0; i < t.size(); ++i)
      t[i] = static_cast<std::uint8_t>(std::lround(255.0 * linear_to_srgb(i / 65535.0)));
    return t;
  }();
  return table;
}

// Segments for a circle of radius r (in framebuffer pixels) so that the
// polygon deviates from the circle by at most kSagitta pixels.
int circle_segments(double r) {
  constexpr double kSagitta = 0.2;
  if (r <= kSagitta) return 8;
  const double n = std::numbers::pi / std::acos(1.0 - kSagitta / r);
  return std::clamp(static_cast<int>(std::ceil(n)), 8, 128);
}

constexpr std::size_t kBatchVertices = 3 * 16384;

}  // namespace

GlCanvas::GlCanvas(int width, int height, int supersample)
    : width_(width), height_(height), supersample_(std::max(1, supersample)) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("GlCanvas: size must be positive");
  if (canvas_active) throw std::logic_error("GlCanvas: one canvas per thread at a time");
  // Large images get fewer samples rather than failing.
  supersample_ = std::min(supersample_, kMaxBufferSide / std::max(width, height));
  if (supersample_ < 1) throw std::invalid_argument("GlCanvas: image larger than 16384 px");
  thread_context().make_current(width * supersample_, height * supersample_);
  canvas_active = true;
  gl().glViewport(0, 0, width * supersample_, height * supersample_);
  gl().glMatrixMode(GL_PROJECTION);
  gl().glLoadIdentity();
  gl().glOrtho(0.0, width, height, 0.0, -1.0, 1.0);  // image pixels, y down
  gl().glMatrixMode(GL_MODELVIEW);
  gl().glLoadIdentity();
  for (GLenum cap : {GL_DEPTH_TEST, GL_BLEND, GL_CULL_FACE, GL_DITHER, GL_LIGHTING, GL_TEXTURE_1D,
                     GL_TEXTURE_2D})
    gl().glDisable(cap);
  gl().glShadeModel(GL_FLAT);
  clear_clip();
}

void GlCanvas::clear(Rgb8 colour) {
  flush();
  gl().glClearColor(colour.r / 255.0f, colour.g / 255.0f, colour.b / 255.0f, 1.0f);
  gl().glClear(GL_COLOR_BUFFER_BIT);
}

void GlCanvas::set_clip(const Rect& clip) {
  flush();
  const int s = supersample_;
  const auto x0 = static_cast<int>(std::floor(clip.x0)), x1 = static_cast<int>(std::ceil(clip.x1));
  const auto y0 = static_cast<int>(std::floor(clip.y0)), y1 = static_cast<int>(std::ceil(clip.y1));
  gl().glEnable(GL_SCISSOR_TEST);
  gl().glScissor(x0 * s, (height_ - y1) * s, (x1 - x0) * s, (y1 - y0) * s);  // GL: y up
}

void GlCanvas::clear_clip() {
  flush();
  gl().glDisable(GL_SCISSOR_TEST);
}

void GlCanvas::push(Point p, Rgb8 c) {
  xy_.push_back(static_cast<float>(p.x));
  xy_.push_back(static_cast<float>(p.y));
  rgb_.insert(rgb_.end(), {c.r, c.g, c.b});
}

void GlCanvas::fill_triangle(Point a, Point b, Point c, Rgb8 colour) {
  push(a, colour);
  push(b, colour);
  push(c, colour);
  if (xy_.size() / 2 >= kBatchVertices) flush();
}

void GlCanvas::fill_mapped_triangles(std::span<const Point> vertices, std::span<const float> t,
                                     const Colormap& map, int bands) {
  if (vertices.size() != t.size() || vertices.size() % 3 != 0)
    throw std::invalid_argument("fill_mapped_triangles: three vertices a triangle, one t each");
  if (vertices.empty()) return;
  flush();
  // Continuous: the whole table, filtered linearly between entries, with
  // t = 0 and 1 on the first and last texel centres. Bands: one texel per
  // band, nearest texel, t = 0..1 across all of them.
  const int texels = bands > 0 ? bands : static_cast<int>(map.size());
  std::vector<std::uint8_t> table;
  for (int k = 0; k < texels; ++k) {
    const Rgb8 c = bands > 0 ? map.at((k + 0.5) / bands) : map.lut()[static_cast<std::size_t>(k)];
    table.insert(table.end(), {c.r, c.g, c.b});
  }
  const float scale = bands > 0 ? 1.0f : (texels - 1.0f) / texels;
  const float offset = bands > 0 ? 0.0f : 0.5f / texels;
  std::vector<float> xy, s;
  xy.reserve(2 * vertices.size());
  s.reserve(t.size());
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    xy.push_back(static_cast<float>(vertices[i].x));
    xy.push_back(static_cast<float>(vertices[i].y));
    s.push_back(offset + scale * t[i]);
  }
  GLuint texture = 0;
  gl().glGenTextures(1, &texture);
  gl().glBindTexture(GL_TEXTURE_1D, texture);
  gl().glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl().glTexImage1D(GL_TEXTURE_1D, 0, GL_RGB8, texels, 0, GL_RGB, GL_UNSIGNED_BYTE, table.data());
  const GLint filter = bands > 0 ? GL_NEAREST : GL_LINEAR;
  gl().glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MIN_FILTER, filter);
  gl().glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MAG_FILTER, filter);
  gl().glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl().glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
  gl().glEnable(GL_TEXTURE_1D);
  gl().glEnableClientState(GL_VERTEX_ARRAY);
  gl().glEnableClientState(GL_TEXTURE_COORD_ARRAY);
  gl().glVertexPointer(2, GL_FLOAT, 0, xy.data());
  gl().glTexCoordPointer(1, GL_FLOAT, 0, s.data());
  gl().glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(vertices.size()));
  gl().glDisableClientState(GL_TEXTURE_COORD_ARRAY);
  gl().glDisableClientState(GL_VERTEX_ARRAY);
  gl().glDisable(GL_TEXTURE_1D);
  gl().glBindTexture(GL_TEXTURE_1D, 0);
  gl().glDeleteTextures(1, &texture);
}

void GlCanvas::fill_rect(const Rect& r, Rgb8 colour) {
  fill_triangle({r.x0, r.y0}, {r.x1, r.y0}, {r.x1, r.y1}, colour);
  fill_triangle({r.x0, r.y0}, {r.x1, r.y1}, {r.x0, r.y1}, colour);
}

void GlCanvas::push_disc(Point centre, double radius_px, Rgb8 colour) {
  const int n = circle_segments(radius_px * supersample_);
  const double step = 2.0 * std::numbers::pi / n;
  Point prev{centre.x + radius_px, centre.y};
  for (int k = 1; k <= n; ++k) {
    const Point next{centre.x + radius_px * std::cos(k * step),
                     centre.y + radius_px * std::sin(k * step)};
    fill_triangle(centre, prev, next, colour);
    prev = next;
  }
}

void GlCanvas::fill_discs(std::span<const Point> centres, double radius_px,
                          std::span<const Rgb8> colours) {
  if (centres.size() != colours.size())
    throw std::invalid_argument("fill_discs: one colour per centre");
  for (std::size_t i = 0; i < centres.size(); ++i) push_disc(centres[i], radius_px, colours[i]);
}

void GlCanvas::stroke(std::span<const Point> points, double width_px, Rgb8 colour, bool closed) {
  const double half = 0.5 * width_px;
  const std::size_t n = points.size();
  const std::size_t segments = closed && n > 2 ? n : (n > 0 ? n - 1 : 0);
  for (std::size_t i = 0; i < segments; ++i) {
    const Point a = points[i], b = points[(i + 1) % n];
    const double len = std::hypot(b.x - a.x, b.y - a.y);
    if (len == 0.0) continue;
    const double nx = -(b.y - a.y) / len * half, ny = (b.x - a.x) / len * half;
    fill_triangle({a.x + nx, a.y + ny}, {b.x + nx, b.y + ny}, {b.x - nx, b.y - ny}, colour);
    fill_triangle({a.x + nx, a.y + ny}, {b.x - nx, b.y - ny}, {a.x - nx, a.y - ny}, colour);
  }
  for (const Point& p : points) push_disc(p, half, colour);  // round joins and caps
}

void GlCanvas::flush() {
  if (xy_.empty()) return;
  gl().glEnableClientState(GL_VERTEX_ARRAY);
  gl().glEnableClientState(GL_COLOR_ARRAY);
  gl().glVertexPointer(2, GL_FLOAT, 0, xy_.data());
  gl().glColorPointer(3, GL_UNSIGNED_BYTE, 0, rgb_.data());
  gl().glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(xy_.size() / 2));
  gl().glDisableClientState(GL_COLOR_ARRAY);
  gl().glDisableClientState(GL_VERTEX_ARRAY);
  xy_.clear();
  rgb_.clear();
}

RgbImage GlCanvas::resolve() {
  flush();
  gl().glFinish();
  const int s = supersample_;
  const std::size_t stride = static_cast<std::size_t>(width_) * static_cast<std::size_t>(s) * 4;
  const std::uint8_t* buffer = thread_context().pixels();
  const auto& lin = to_linear16();
  const auto& enc = to_srgb8();
  const std::uint32_t count = static_cast<std::uint32_t>(s * s);
  RgbImage image(width_, height_);
  std::vector<std::uint32_t> sums(static_cast<std::size_t>(width_) * 3);
  for (int y = 0; y < height_; ++y) {
    std::fill(sums.begin(), sums.end(), 0u);
    for (int sy = 0; sy < s; ++sy) {
      const std::uint8_t* row = buffer + static_cast<std::size_t>(y * s + sy) * stride;
      for (int x = 0; x < width_ * s; ++x)
        for (int c = 0; c < 3; ++c)
          sums[static_cast<std::size_t>(x / s * 3 + c)] += lin[row[x * 4 + c]];
    }
    for (std::size_t i = 0; i < sums.size(); ++i)
      image.rgb[static_cast<std::size_t>(y) * sums.size() + i] = enc[(sums[i] + count / 2) / count];
  }
  return image;
}

GlCanvas::~GlCanvas() {
  canvas_active = false;
}

}  // namespace gearsph::render
