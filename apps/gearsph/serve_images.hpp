#pragma once
// The renderer behind GET /jobs/{id}/images/{field}.png: a frame of a job's
// results.h5 drawn by the OSMesa field renderer. Empty (the endpoint then
// answers 501) in a build without the results and render layers.
#include "server/image_provider.hpp"

namespace gearsph::cli {

server::ImageProvider results_image_provider();

}  // namespace gearsph::cli
