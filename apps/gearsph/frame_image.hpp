#pragma once
// A frame of a finished run's results.h5 drawn by the field renderer: what
// `gearsph render` writes and what the service answers at
// GET /jobs/{id}/images/{field}.png (serve_images.hpp). A frame that cannot
// be drawn is a FrameImageError naming why; the command turns it into a
// message and an exit status, the service into an HTTP status.
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>

namespace gearsph::cli {

struct FrameImageRequest {
  std::string field = "von_mises";              // von_mises, pressure, velocity, body, ...
  std::int64_t frame = -1;                      // snapshot index; -1: the last one
  std::optional<std::array<double, 4>> zoom_m;  // x0, y0, x1, y1 [m], x0 < x1, y0 < y1
  // The colour scale, lo < hi in the field's SI unit; values beyond take the
  // end colours. Default: from the frame's values.
  std::optional<std::array<double, 2>> range;
  // The particles as discs of their own value; by default a field is drawn
  // as contours inside the outlines, smoothed for the drawing
  // (render/particle_mesh.hpp).
  bool particles = false;
};

// Why a frame was not drawn.
enum class FrameImageFault {
  unknown_field,    // no field of that name
  no_colour_scale,  // a range asked of a field drawn in categories (body)
  no_frames,        // the run wrote none (output.frames = 0)
  no_such_frame,    // past the run's last frame
  no_results,       // no results.h5 there, or not one that can be read
  drawing_failed,   // reading the frame or drawing it failed
};

class FrameImageError : public std::runtime_error {
 public:
  FrameImageError(FrameImageFault fault, const std::string& detail)
      : std::runtime_error(detail), fault_(fault) {}
  FrameImageFault fault() const { return fault_; }

 private:
  FrameImageFault fault_;
};

// How much the drawn field zig-zags from particle to particle, against the
// particles' own values (render/particle_mesh.hpp, zigzag_indicator), over
// the particles in the window drawn; a drawing of the particles or of
// categories has none (counted 0).
struct DrawnFieldStats {
  double particles_zigzag = 0.0, drawn_zigzag = 0.0;
  double particles_max = 0.0, drawn_max = 0.0;  // the largest value in the window
  std::size_t counted = 0;
};

// The PNG of one frame of run_dir/results.h5 (and, when `stats` is given,
// the drawn field's zig-zag). Throws FrameImageError, and only that.
// Defined in builds with the results and render layers.
std::string draw_frame_png(const std::filesystem::path& run_dir, const FrameImageRequest& request,
                           DrawnFieldStats* stats = nullptr);

}  // namespace gearsph::cli
