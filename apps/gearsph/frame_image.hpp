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

// The PNG of one frame of run_dir/results.h5. Throws FrameImageError, and
// only that. Defined in builds with the results and render layers.
std::string draw_frame_png(const std::filesystem::path& run_dir, const FrameImageRequest& request);

}  // namespace gearsph::cli
