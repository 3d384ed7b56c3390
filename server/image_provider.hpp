#pragma once
// The hook through which the application plugs a renderer into
// GET /jobs/{id}/images/{field}.png. The server keeps what it returns in a
// bounded cache in memory; without a provider the endpoint answers 501.
#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

namespace gearsph::server {

struct ImageRequest {
  std::string field;                            // e.g. "von_mises"; [A-Za-z0-9_]+
  std::int64_t frame = -1;                      // snapshot index; -1: the last one
  std::optional<std::array<double, 4>> zoom_m;  // x0, y0, x1, y1 [m], x0 < x1, y0 < y1
  // The colour scale, lo < hi in the field's SI unit; values beyond take the
  // end colours. Default: from the frame's values.
  std::optional<std::array<double, 2>> range;
};

struct ImageResult {
  int status =
      200;          // 200, or the HTTP status of the refusal (404 unknown frame, 400 unknown field)
  std::string png;  // the image when status is 200
  std::string detail;  // one sentence when status is not 200
};

// Called on a handler thread (never an I/O thread), possibly concurrently for
// different requests; job_dir holds results.h5 / results.xmf of a finished job.
using ImageProvider =
    std::function<ImageResult(const std::filesystem::path& job_dir, const ImageRequest&)>;

}  // namespace gearsph::server
