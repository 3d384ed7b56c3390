#pragma once
// `gearsph bench pareto`: error against cost over kernel, spacing, h/dx,
// Courant number and formulation, for the oscillating plate, Hertz contact
// and the static gear's root bending (docs/speed-accuracy.md, "Speed
// against accuracy"). Each sweep writes its rows (OUT/pareto_NAME.csv), its
// Pareto front (pareto_NAME_front.csv) and a chart (pareto_NAME.png), and
// prints them.
#include <filesystem>
#include <string>

namespace gearsph::cli::bench {

// The sweeps whose names `cases` holds (hertz, gear, plate), in that order,
// into the directory `out`, which exists.
void pareto_sweeps(const std::filesystem::path& out, const std::string& cases, bool quick,
                   int threads);

}  // namespace gearsph::cli::bench
