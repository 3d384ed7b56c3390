// gearsph render / gearsph plot: pictures of a finished run directory, the
// same the service draws (GET /jobs/{id}/images), without a server.
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "apps/gearsph/cli.hpp"
#include "apps/gearsph/frame_image.hpp"
#include "render/plot_image.hpp"
#include "render/png_io.hpp"

namespace gearsph::cli {

namespace {

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, sep);) out.push_back(item);
  return out;
}

// `count` finite numbers separated by commas, or invalid_argument(usage).
std::vector<double> numbers(const std::string& text, std::size_t count, const std::string& usage) {
  const std::vector<std::string> v = split(text, ',');
  if (v.size() != count) throw std::invalid_argument(usage + ", got '" + text + "'");
  std::vector<double> out(count);
  for (std::size_t k = 0; k < count; ++k) {
    std::size_t used = 0;
    try {
      out[k] = std::stod(v[k], &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != v[k].size() || !std::isfinite(out[k])) {
      throw std::invalid_argument(usage + ": '" + v[k] + "' is not a number");
    }
  }
  return out;
}

void write_png(const std::string& path, const std::string& bytes) {
  std::ofstream f(path, std::ios::binary);
  f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!f) throw std::runtime_error("cannot write " + path);
}

constexpr const char* kResultsFileName = "results.h5";

// --field, --frame, --zoom, --range and --particles.
FrameImageRequest read_frame_request(Args& args) {
  FrameImageRequest request;
  request.field = args.option("field").value_or("von_mises");
  request.frame = args.integer("frame", -1);
  if (const auto zoom = args.option("zoom")) {
    const std::string usage = "--zoom takes x0,y0,x1,y1 in metres with x1 > x0 and y1 > y0";
    const std::vector<double> z = numbers(*zoom, 4, usage);
    if (!(z[2] > z[0] && z[3] > z[1])) throw std::invalid_argument(usage + ", got '" + *zoom + "'");
    request.zoom_m = {z[0], z[1], z[2], z[3]};
  }
  if (const auto range = args.option("range")) {
    const std::string usage = "--range takes lo,hi in the field's SI unit with lo < hi";
    const std::vector<double> r = numbers(*range, 2, usage);
    if (!(r[0] < r[1])) throw std::invalid_argument(usage + ", got '" + *range + "'");
    request.range = std::array<double, 2>{r[0], r[1]};
  }
  request.particles = args.flag("particles");
  return request;
}

// The run directory the one positional argument names: a run directory, or
// its results.h5.
std::filesystem::path run_directory(const std::vector<std::string>& pos) {
  if (pos.size() != 1) throw std::invalid_argument("render: one run directory or results.h5");
  std::filesystem::path dir = pos.front();
  if (dir.extension() == ".h5") {
    if (dir.filename() != kResultsFileName) {
      throw std::invalid_argument("render reads a run's " + std::string(kResultsFileName) +
                                  " (or its directory), not " + dir.string());
    }
    dir = dir.parent_path().empty() ? "." : dir.parent_path();
  }
  return dir;
}

// The exit status of a frame that was not drawn: 1 when the results could not
// be read or drawn, 2 when the request asks for what they do not hold.
int exit_status(FrameImageFault fault) {
  switch (fault) {
    case FrameImageFault::no_results:
    case FrameImageFault::drawing_failed:
      return 1;
    case FrameImageFault::unknown_field:
    case FrameImageFault::no_colour_scale:
    case FrameImageFault::no_frames:
    case FrameImageFault::no_such_frame:
      break;
  }
  return 2;
}

int render_one(const std::filesystem::path& dir, const FrameImageRequest& request,
               const std::string& out) {
  std::string png;
  DrawnFieldStats stats;
  try {
    png = draw_frame_png(dir, request, &stats);
  } catch (const FrameImageError& e) {
    std::fprintf(stderr, "gearsph render: %s\n", e.what());
    return exit_status(e.fault());
  }
  write_png(out, png);
  std::printf("wrote %s\n", out.c_str());
  if (stats.counted > 0) {
    std::printf(
        "zig-zag indicator over the %zu particles drawn: %.3f drawn, %.3f the particles' own\n",
        stats.counted, stats.drawn_zigzag, stats.particles_zigzag);
    std::printf("largest value drawn %.6g, the particles' largest %.6g (SI)\n", stats.drawn_max,
                stats.particles_max);
  }
  return 0;
}

// --frames all: OUT is a directory of FIELD_NNNN.png, frame by frame until
// the results have no more.
int render_all(const std::filesystem::path& dir, FrameImageRequest request,
               const std::string& out) {
  std::filesystem::create_directories(out);
  int written = 0;
  for (request.frame = 0;; ++request.frame) {
    std::string png;
    try {
      png = draw_frame_png(dir, request);
    } catch (const FrameImageError& e) {
      const bool past_the_last =
          e.fault() == FrameImageFault::no_frames || e.fault() == FrameImageFault::no_such_frame;
      if (past_the_last) break;
      std::fprintf(stderr, "gearsph render: frame %lld: %s\n",
                   static_cast<long long>(request.frame), e.what());
      return exit_status(e.fault());
    }
    char name[64];
    std::snprintf(name, sizeof name, "/%s_%04lld.png", request.field.c_str(),
                  static_cast<long long>(request.frame));
    write_png(out + name, png);
    ++written;
  }
  if (written == 0) {
    std::fprintf(stderr, "gearsph render: %s has no committed frames (output.frames 0?)\n",
                 dir.string().c_str());
    return 2;
  }
  std::printf("wrote %d frames to %s\n", written, out.c_str());
  return 0;
}

}  // namespace

int cmd_render(Args& args) {
  const std::string out = args.option("out").value_or("");
  const std::string frames = args.option("frames").value_or("");
  const FrameImageRequest request = read_frame_request(args);
  const std::filesystem::path dir = run_directory(args.positional());
  if (out.empty()) throw std::invalid_argument("render: --out is required");
  if (!frames.empty() && frames != "all") {
    throw std::invalid_argument("render: --frames takes 'all' (or use --frame N)");
  }
  return frames.empty() ? render_one(dir, request, out) : render_all(dir, request, out);
}

// History columns of DIR/history.csv against time, one series each.
int cmd_plot(Args& args) {
  const std::string out = args.option("out").value_or("");
  const std::vector<std::string> wanted = split(args.option("columns").value_or(""), ',');
  render::Plot plot;
  plot.title = args.option("title").value_or("");
  plot.y_label = args.option("ylabel").value_or("");
  const double scale = std::stod(args.option("scale").value_or("1"));
  const std::vector<std::string> pos = args.positional();
  if (pos.size() != 1) throw std::invalid_argument("plot: one run directory expected");
  const std::string& dir = pos.front();
  if (out.empty() || wanted.empty() || wanted.front().empty()) {
    throw std::invalid_argument("plot: --columns A,B and --out FILE.png are required");
  }
  std::ifstream f(dir + "/history.csv");
  if (!f) throw std::invalid_argument("plot: no history.csv in " + dir);
  std::string line;
  std::getline(f, line);
  const std::vector<std::string> header = split(line, ',');
  std::vector<std::size_t> index;
  for (const std::string& w : wanted) {
    std::size_t k = 0;
    while (k < header.size() && header[k] != w) ++k;
    if (k == header.size()) throw std::invalid_argument("plot: history.csv has no column " + w);
    index.push_back(k);
    plot.series.push_back({w, {}, {}, {}});
  }
  plot.x_label = "time [ms]";
  while (std::getline(f, line)) {
    const std::vector<std::string> v = split(line, ',');
    if (v.size() != header.size()) continue;
    const double t = 1e3 * std::stod(v[0]);
    for (std::size_t s = 0; s < index.size(); ++s) {
      plot.series[s].x.push_back(t);
      plot.series[s].y.push_back(scale * std::stod(v[index[s]]));
    }
  }
  const std::vector<unsigned char> png = render::render_plot_png(plot);
  write_png(out, std::string(png.begin(), png.end()));
  std::printf("wrote %s\n", out.c_str());
  return 0;
}

}  // namespace gearsph::cli
