#pragma once
// A simulated rack_pinion static check rated (issue: verdicts from the
// simulation): method B for the job's pinion, rack, materials and load,
// and the same verdict with the simulation's stresses in place of ISO's
// nominal ones. The fillet's recovered tension peak replaces F_t/(b m) Y_F
// Y_S (a method A reading: the stress at the notch, computed), keeping
// ISO's notch sensitivity, surface and size factors on the permissible
// side; the Hertz pressure on tooth 0's resolved force (and the resolved
// pressure, where the check resolved the contact) replaces sigma_H0.
#include <nlohmann/json.hpp>

#include "solver/geometry/gear_profile.hpp"

namespace gearsph::gear::iso6336 {

// The rating document (schemas/rating.schema.json) of a job's pinion with
// its rack, or null when a material carries no strength. `options` is the
// scene's "rating" block (required safeties, life, K_A, speed). Throws
// InvalidRating when it cannot be rated (pointers of the rating document).
nlohmann::json rack_pinion_rating_document(const geometry::PinionGeometry& pinion,
                                           double face_width_m,
                                           const nlohmann::json& pinion_material,
                                           const nlohmann::json& rack_material, double load_N,
                                           double omega_rad_s, const nlohmann::json& options);

// analysis.rating of a static check (the analysis' static_check block):
// method B's verdict and the simulation's, side by side, and the governing
// mode.
nlohmann::json rating_from_static_check(const nlohmann::json& document,
                                        const nlohmann::json& static_check);

// analysis.rating of a loaded dynamic run (the analysis' dynamics block):
// method B's verdict for the job's pair, load and speed, with ISO's K_v
// beside the one the run measured (peak over mean mesh force over its
// steady mesh, analysis.dynamics.K_v), and method B's safeties again with
// the measured K_v in place of ISO's. A run that never reached a steady
// mesh gets a null measured K_v with the reason, never an estimate.
nlohmann::json rating_from_dynamics(const nlohmann::json& document, const nlohmann::json& dynamics);

// analysis.rating.fe_check: the FE check's fillet tension peak and its
// Hertz patch pressure (fe_summary.json, for the FE's own load on tooth 0)
// rated under the factors and permissible stresses of `rating` (a static
// check's analysis.rating), beside the simulation's S_F and S_H.
nlohmann::json rating_from_fe_check(const nlohmann::json& rating, const nlohmann::json& fe_summary);

}  // namespace gearsph::gear::iso6336
