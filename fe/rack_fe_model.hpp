#pragma once
// The finite-element model of the rack tooth that meets the pinion of
// gear_fe_model.hpp, for the rack's share of the mesh compliance: the
// scene's rack (its profile is the pinion's cutting tool; one tooth on its
// back, cut at the space centres), plane strain, loaded on its flank by the
// same Hertzian pressure as the pinion's, where the line of action crosses
// the flank for the pinion's load radius. The back is held in y and pushed
// in x by a uniform traction that balances the load, as the scene guides
// and loads the rack's back. The compliance is that of the load's
// work-conjugate displacement relative to the rack's mean displacement,
// the reference of the scene's transmission error (the mean of every rack
// particle): so it does not depend on how the back is held (held fixed
// instead, it reads the same to 0.5 %: docs/gears.md).
#include <filesystem>
#include <string>

#include "fe/calculix_solver.hpp"
#include "fe/external_program.hpp"
#include "fe/gear_fe_model.hpp"

namespace gearsph::fe {

struct RackFeResult {
  TriMesh mesh;
  FeSolution solution;
  Point load_point;                  // the patch centre on the rack's flank (rack frame) [m]
  double load_displacement_m = 0.0;  // work-conjugate to the Hertz pressure
  double mean_displacement_m = 0.0;  // the rack's area mean, along the load
  // (load - mean) per unit line load F_n / b [m^2/N].
  double compliance_m2_per_N = 0.0;
  // The flank at the patch centre, along the load [m], and (centre - mean)
  // per unit line load [m^2/N]: the rack's part of the approach
  // (GearFeResult::centre_displacement_m).
  double centre_displacement_m = 0.0;
  double centre_compliance_m2_per_N = 0.0;
  double mesh_s = 0.0, solve_s = 0.0;
};

// `load`: the pinion's patch (solve_gear_fe), whose half-width, peak
// pressure and radius the rack's takes. `element_size_m` at the load.
RackFeResult solve_rack_fe(const GearFeCase& c, const GearLoadPatch& load, double element_size_m,
                           const FeTools& tools, const std::filesystem::path& work_dir,
                           const std::string& name, int threads, double timeout_s);

}  // namespace gearsph::fe
