#include "solver/geometry/svg.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace gearsph::geometry {

namespace {

constexpr double kMmPerM = 1e3;
constexpr double kFontPx = 14.0;
constexpr double kHeaderPx = 1.5 * kFontPx;  // room for the title
constexpr double kFooterPx = 3.0 * kFontPx;  // room for the scale bar

// Locale-independent fixed notation, two decimals (0.01 px).
std::string num(double v) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, 2);
  return std::string(buf, res.ptr);
}

// Shortest round-trip form (the scale bar label: 0.5, 2, 10).
std::string label(double v) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

std::string escaped(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// World (m, y up) to picture (px, y down).
struct Frame {
  Box box;
  double scale = 1.0;   // px per metre
  double margin = 0.0;  // px
  double width() const { return (box.hi.x - box.lo.x) * scale + 2.0 * margin; }
  double height() const {
    return (box.hi.y - box.lo.y) * scale + 2.0 * margin + kHeaderPx + kFooterPx;
  }
  double px(double x) const { return (x - box.lo.x) * scale + margin; }
  double py(double y) const { return (box.hi.y - y) * scale + margin + kHeaderPx; }
};

Frame make_frame(const SvgDrawing& d) {
  std::vector<Point> all;
  for (const auto& l : d.lines) all.insert(all.end(), l.points.begin(), l.points.end());
  for (const auto& s : d.dots) all.insert(all.end(), s.points.begin(), s.points.end());
  Frame f;
  f.box = all.empty() ? Box{{0.0, 0.0}, {1e-3, 1e-3}} : bounding_box(all);
  f.scale = d.px_per_mm * kMmPerM;
  f.margin = d.margin_px;
  return f;
}

// Longest 1-2-5 length in mm that is at most a quarter of the picture.
double scale_bar_mm(const Frame& f) {
  const double limit = 0.25 * (f.box.hi.x - f.box.lo.x) * kMmPerM;
  if (!(limit > 0.0)) return 1.0;
  const double decade = std::pow(10.0, std::floor(std::log10(limit)));
  for (const double step : {5.0, 2.0, 1.0}) {
    if (step * decade <= limit) return step * decade;
  }
  return decade;
}

void write_lines(std::ostream& os, const Frame& f, const SvgDrawing& d) {
  for (const auto& l : d.lines) {
    os << (l.closed ? "<polygon" : "<polyline") << " fill=\"none\" stroke=\"" << escaped(l.colour)
       << "\" stroke-width=\"" << num(l.width_px) << "\" stroke-linejoin=\"round\" points=\"";
    for (const Point& p : l.points) os << num(f.px(p.x)) << ',' << num(f.py(p.y)) << ' ';
    os << "\"/>\n";
  }
}

void write_dots(std::ostream& os, const Frame& f, const SvgDrawing& d) {
  for (const auto& s : d.dots) {
    const double r = s.radius_m > 0.0 ? s.radius_m * f.scale : 1.5;
    os << "<g fill=\"" << escaped(s.colour) << "\">\n";
    for (const Point& p : s.points) {
      os << "<circle cx=\"" << num(f.px(p.x)) << "\" cy=\"" << num(f.py(p.y)) << "\" r=\"" << num(r)
         << "\"/>\n";
    }
    os << "</g>\n";
  }
}

void write_scale_bar(std::ostream& os, const Frame& f) {
  const double mm = scale_bar_mm(f);
  const double x0 = f.margin, y = f.height() - kFontPx;
  const double x1 = x0 + mm / kMmPerM * f.scale;
  os << "<line x1=\"" << num(x0) << "\" y1=\"" << num(y) << "\" x2=\"" << num(x1) << "\" y2=\""
     << num(y) << "\" stroke=\"black\" stroke-width=\"3\"/>\n";
  os << "<text x=\"" << num(x1 + 6.0) << "\" y=\"" << num(y + 5.0)
     << "\" font-family=\"sans-serif\" "
     << "font-size=\"" << num(kFontPx) << "\">" << label(mm) << " mm</text>\n";
}

}  // namespace

std::string svg_document(const SvgDrawing& d) {
  const Frame f = make_frame(d);
  std::ostringstream os;
  os << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
     << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << num(f.width()) << "\" height=\""
     << num(f.height()) << "\" viewBox=\"0 0 " << num(f.width()) << ' ' << num(f.height())
     << "\">\n"
     << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
     << "<text x=\"" << num(f.margin) << "\" y=\"" << num(kFontPx)
     << "\" font-family=\"sans-serif\" "
     << "font-size=\"" << num(kFontPx) << "\">" << escaped(d.title) << "</text>\n";
  write_dots(os, f, d);
  write_lines(os, f, d);
  write_scale_bar(os, f);
  os << "</svg>\n";
  return os.str();
}

void write_svg(const std::string& path, const SvgDrawing& drawing) {
  std::ofstream file(path);
  if (!file) throw std::runtime_error("cannot open " + path + " for writing");
  file << svg_document(drawing);
  if (!file) throw std::runtime_error("cannot write " + path);
}

}  // namespace gearsph::geometry
