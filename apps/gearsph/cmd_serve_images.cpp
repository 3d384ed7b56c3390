// GET /jobs/{id}/images/{field}.png: one frame of results.h5 drawn as
// `gearsph render` draws it (frame_image.hpp), its refusals told in HTTP
// statuses.
#include "apps/gearsph/serve_images.hpp"

#if defined(GEARSPH_WITH_RESULTS) && defined(GEARSPH_WITH_RENDER)

#include <exception>
#include <string>

#include "apps/gearsph/frame_image.hpp"

namespace gearsph::cli {

namespace {

int http_status(FrameImageFault fault) {
  switch (fault) {
    case FrameImageFault::unknown_field:
    case FrameImageFault::no_colour_scale:
      return 400;
    case FrameImageFault::no_frames:
    case FrameImageFault::no_such_frame:
      return 404;
    case FrameImageFault::no_results:
    case FrameImageFault::drawing_failed:
      break;
  }
  return 500;
}

}  // namespace

server::ImageProvider results_image_provider() {
  return [](const std::filesystem::path& job_dir, const server::ImageRequest& request) {
    server::ImageResult out;
    try {
      const FrameImageRequest frame{request.field, request.frame, request.zoom_m, request.range};
      out.png = draw_frame_png(job_dir, frame);
    } catch (const FrameImageError& e) {
      out.status = http_status(e.fault());
      out.detail = e.what();
    } catch (const std::exception& e) {  // e.g. out of memory
      out.status = 500;
      out.detail = std::string("the image could not be rendered: ") + e.what();
    }
    return out;
  };
}

}  // namespace gearsph::cli

#else

namespace gearsph::cli {

server::ImageProvider results_image_provider() {
  return {};
}

}  // namespace gearsph::cli

#endif
