#pragma once
// The finite-element model of the loaded pinion tooth, made to match the
// SPH model of solver/scene/rack_pinion.cpp: the same generated outline
// (gear_profile.hpp), tooth 0 with its neighbours on a rim that is held
// where the SPH hub ring holds it, the same normal force along the line of
// action at the same radius, and the fillet stress read on the same curves
// with the same definitions (gear/fillet.hpp).
//
// Model (gear frame of gear_profile.hpp: tooth 0 points along -y):
//  - the teeth the SPH static check models (tooth 0 and its neighbours at
//    least: rack_pinion.hpp, static_check_pinion_teeth) and the rim down to
//    `fixed_radius`, cut by
//    radial lines through the middles of the outer spaces; the cut sides
//    are free, the inner arc is held (u = 0): the SPH particles inside the
//    drive radius move with the hub, which a quasi-static run holds still.
//    Or the whole gear, held on a bore of that radius;
//  - plane strain, six-node triangles (CalculiX CPE6), unit thickness; the
//    forces are per metre of face width and reported per gear;
//  - element size `fillet_size` along both fillets of tooth 0 and at the
//    load, growing to five times that away from them;
//  - the normal force as a Hertzian pressure on the flank (line contact of
//    the involute, radius of curvature sqrt(r^2 - r_b^2), on the flat rack
//    flank: Johnson, Contact Mechanics, 1985, eq. 4.45), not a point force.
//    A point force in 2D is a singularity whose local stresses and
//    displacements grow without bound as the mesh is refined; the rack
//    spreads it over the contact width 2a, and the fillet stress a few
//    millimetres away is then independent of the mesh near the load
//    (Saint-Venant). A patch that would run over the tip corner is moved
//    down the flank to end at the corner (the load radius reported is the
//    patch centre's).
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "fe/calculix_solver.hpp"
#include "fe/external_program.hpp"
#include "fe/gmsh_mesher.hpp"
#include "solver/gear/fillet.hpp"
#include "solver/geometry/gear_profile.hpp"

namespace gearsph::fe {

struct GearFeCase {
  geometry::PinionSpec pinion;
  double E_Pa = 1.73e11, nu = 0.3;            // pinion
  double rack_E_Pa = 1.73e11, rack_nu = 0.3;  // for the contact width only
  double face_width_m = 0.02;
  double normal_force_N = 0.0;  // per gear, along the line of action
  double load_radius_m = 0.0;   // where the load acts on tooth 0's flank
  // The loaded flank of tooth 0: -1 the one on the -x side (a clockwise
  // pinion driving the rack), +1 the +x side.
  int flank_side = -1;
  // The rack the pinion meshes with (the scene's: its cutting tool's
  // profile, one tooth on a back of `rack_back_m`), for its compliance
  // (rack_fe_model.hpp).
  double rack_back_m = 0.0;
  double rack_backlash_m = 0.0;
  // Teeth first_tooth..last_tooth (numbered as the SPH scene numbers them,
  // tooth 0 loaded), or all of them, held on a bore of fixed_radius_m.
  int first_tooth = -1, last_tooth = 1;
  bool whole_gear = false;
  double fixed_radius_m = 0.0;
};

// The whole gear: asked for, or as many teeth as it has.
inline bool models_whole_gear(const GearFeCase& c) {
  return c.whole_gear || c.last_tooth - c.first_tooth + 1 >= c.pinion.teeth;
}

// Element sizes [m]: `fillet` along both fillets of tooth 0 (within
// `fillet_band` of them) and at the load, growing linearly to `max` at
// `grow_to` from them.
struct GearMeshSizes {
  double fillet = 0.0, load = 0.0, max = 0.0;
  double fillet_band = 0.0, load_band = 0.0, grow_to = 0.0;
};
// The defaults for a fillet size: the bands scale with the module, so that
// halving `fillet_size` halves every element.
GearMeshSizes gear_mesh_sizes(const geometry::PinionGeometry& pinion, double fillet_size_m);

// The fillet element sizes of the convergence pair for this pinion: 1/12
// and 1/24 of the ISO 6336-3 fillet radius at the critical section, 0.2 and
// 0.1 mm for the seed paper's pinion (rho_F = 2.38 mm), rounded to two digits.
std::vector<double> default_fillet_sizes(const geometry::PinionGeometry& pinion);

struct GearLoadPatch {
  Point centre;         // patch centre on the flank (gear frame) [m]
  Point direction;      // unit, the force on the tooth: along the line of action
  double radius_m = 0;  // of the centre
  double requested_radius_m = 0;
  double half_width_m = 0;      // Hertz a
  double peak_pressure_Pa = 0;  // Hertz p0
  double curvature_radius_m = 0;
  Point applied_N;  // sum of the nodal forces, per gear
};

struct GearFeResult {
  GearMeshSizes sizes;
  TriMesh mesh;
  FeSolution solution;
  geometry::Polygon outline;             // outer boundary (gear frame)
  std::vector<geometry::Polygon> holes;  // the bore of a whole gear
  gear::ToothFillets fillets;
  gear::FilletStress stress;
  GearLoadPatch load;
  Point reaction_N;  // total support reaction, per gear
  // The load's displacement, work-conjugate to the Hertz pressure (sum of
  // f . u over the loaded nodes, over the force) [m]: the tooth's bending
  // and shear, the rim's, and the pinion's side of the Hertz indentation,
  // from the held radius. Per unit line load it is the pinion's share of the
  // mesh compliance that the SPH static check splits (docs/gears.md).
  double load_displacement_m = 0.0;
  // The flank's displacement at the patch centre along the load [m]. The
  // approach of two bodies in Hertz contact is that of their contact
  // centres; the work-conjugate mean above is less by each body's share of
  // a^2 / (8 R*) (docs/gears.md, "The pair against finite elements").
  double centre_displacement_m = 0.0;
  double curve_to_mesh_m = 0.0;  // largest distance of a fillet sample from the mesh boundary
  double mesh_s = 0.0, solve_s = 0.0;
};

// The colour scale of the stress figures of tooth 0 [Pa]: +-1.25 times the
// larger fillet peak, so the fillets are read in full and the load's
// contact zone goes beyond (its end colour). fe_images.cpp draws the FE
// field with it; fe_summary.json gives it (image_range_Pa) for the SPH field
// that the dashboard draws beside.
std::array<double, 2> root_image_range_Pa(const GearFeResult& r);

// Nodal forces per unit thickness of the Hertzian pressure
// p0 sqrt(1 - (d/a)^2) of `patch` (its half-width and peak) about `centre`
// on `edges`, scaled so that they add up to `line_load` [N/m] exactly (the
// quadrature of the sqrt-shaped patch on edges it covers in part is good to
// about 1e-4).
std::vector<Point> hertz_forces(const TriMesh& mesh, const std::vector<BoundaryEdge>& edges,
                                Point centre, const GearLoadPatch& patch, double line_load);
// The displacement along `direction` at the boundary point of `edges`
// nearest `point`, interpolated along its edge [m].
double boundary_displacement(const TriMesh& mesh, const std::vector<BoundaryEdge>& edges,
                             const FeSolution& solution, Point point, Point direction);
// The displacement work-conjugate to `forces`: sum f . u / |sum f| [m].
double load_displacement(const std::vector<Point>& forces, const FeSolution& solution);

// A model of one material on the mesh gmsh makes of `spec`, with no
// supports or loads yet; `mesh_s` gets gmsh's time.
FeModel meshed_model(const MeshSpec& spec, double E_Pa, double nu, const FeTools& tools,
                     const std::filesystem::path& work_dir, const std::string& name,
                     double timeout_s, double& mesh_s);

// Builds, meshes and solves the model in `work_dir` (files `name`.geo,
// .msh, .inp, .frd, ... stay there). `sample_step_m`: spacing of the fillet
// curve samples.
GearFeResult solve_gear_fe(const GearFeCase& c, const GearMeshSizes& sizes, double sample_step_m,
                           const FeTools& tools, const std::filesystem::path& work_dir,
                           const std::string& name, int threads, double timeout_s);

}  // namespace gearsph::fe
