#pragma once
// The fillet stress of a static gear check against arc length, drawn after
// the run as `fillet_curves.png` in its directory (docs/gears.md): sigma_1
// along the tension fillet and sigma_3 along the compression fillet, from
// the middle of the tooth space to the form circle, with the
// finite-element curves of the same tooth beside them when the run has
// them (`"fe_check": true`, fe_fillet_curves.json).
#include <vector>

#include <nlohmann/json.hpp>

namespace gearsph::render {

// The PNG of `static_check` (summary.analysis.static_check, with its
// fillet_curves); `fe_curves` is fe_fillet_curves.json or null.
std::vector<unsigned char> fillet_plot_png(const nlohmann::json& static_check,
                                           const nlohmann::json& fe_curves);

// Registers the drawing as a summary addition of every run (run, serve,
// worker); runs without a static check are left alone.
void register_fillet_plot();

}  // namespace gearsph::render
