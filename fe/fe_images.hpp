#pragma once
// The FE check's pictures, drawn by the renderer (render/mesh_image.hpp,
// render/plot_image.hpp): the reference mesh's von Mises and largest
// principal stress over the whole model and closer around tooth 0's root,
// its mesh there, and the fillet stress against arc length for every mesh.
#include <filesystem>
#include <string>
#include <vector>

#include "fe/gear_fe_model.hpp"

namespace gearsph::fe {

// Writes the PNG files into `dir`; returns their names.
std::vector<std::string> write_fe_images(const std::vector<GearFeResult>& meshes,
                                         const std::filesystem::path& dir,
                                         const std::string& title);

}  // namespace gearsph::fe
