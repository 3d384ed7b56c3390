#pragma once
// A linear-elastic plane-strain problem on a six-node triangle mesh, solved
// by CalculiX (ccx): the input deck (CPE6 elements, supports, nodal
// forces), the run, and the results read back from its .frd (nodal
// displacements; stresses extrapolated from the integration points to the
// nodes and averaged between elements by ccx) and .dat (total support
// reaction). Unit thickness: forces are per metre of face width.
#include <filesystem>
#include <string>
#include <vector>

#include "fe/external_program.hpp"
#include "fe/tri_mesh.hpp"

namespace gearsph::fe {

// Zero displacement along x and/or y at some nodes.
struct Support {
  std::vector<int> nodes;
  bool x = true, y = true;
};

struct FeModel {
  TriMesh mesh;
  double E_Pa = 0.0, nu = 0.0;
  std::vector<Support> supports;
  std::vector<Point> nodal_forces;  // one per node [N per metre of thickness]
};

// Cauchy stress at a node [Pa]; zz from the plane-strain constraint.
struct NodalStress {
  double xx = 0.0, yy = 0.0, zz = 0.0, xy = 0.0;
  double von_mises() const;
  double max_principal() const;  // in-plane
  double min_principal() const;
};

struct FeSolution {
  std::vector<Point> displacement;  // [m]
  std::vector<NodalStress> stress;
  Point reaction;  // sum over all supports [N/m]
  Point applied;   // sum of the nodal forces [N/m]
  double wall_s = 0.0;
};

std::string calculix_deck(const FeModel& model);
// The DISP and STRESS blocks of an ASCII .frd file, for nodes 1..nodes.
FeSolution read_frd(const std::string& text, std::size_t nodes);
// The total reaction of the deck's support set, from the .dat file.
Point read_reaction_total(const std::string& dat);

// Writes `name`.inp in `work_dir`, runs ccx with `threads` threads, reads
// the results; throws FeFailed with the end of ccx's output on failure.
FeSolution solve_with_calculix(const FeModel& model, const FeTools& tools,
                               const std::filesystem::path& work_dir, const std::string& name,
                               int threads, double timeout_s);

}  // namespace gearsph::fe
