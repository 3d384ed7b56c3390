#pragma once
// A root crack in a static check of the rack_pinion scene (docs/cracks.md,
// "The gear"): a straight crack drawn from a point of tooth 0's tension
// fillet, grown in quasi-static stages by the machinery the cracked plate
// uses (scene/crack_stages.hpp), until it runs through the tooth, into the
// rim towards the bore, or is arrested.
#include <memory>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "solver/gear/fillet.hpp"
#include "solver/geometry/polygon.hpp"

namespace gearsph {
struct Scene;
}

namespace gearsph::scenes {

struct GearLayout;

// Where the crack lives: what the builder knows of the pinion as modelled.
struct GearCrackSite {
  geometry::Polygon outline;  // the modelled pinion in the world [m]
  geometry::Point centre;     // the pinion's centre [m]
  double r_drive = 0.0;       // the held ring's outer edge: the rim's bore [m]
  double root_radius = 0.0, tip_radius = 0.0;
  double tooth_axis = 0.0;        // tooth 0's axis angle in the world [rad]
  double half_pitch = 0.0;        // half the angular pitch [rad]
  double thickness = 0.0;         // tooth 0's root chord s_Fn (ISO 6336-3) [m]
  double spacing = 0.0;           // the particles' spacing along the crack's way [m]
  gear::ToothFillets fillets;     // tooth 0's, its tension fillet the crack's start
  std::size_t monitor_tooth = 0;  // tooth 0's index in the RootMonitor
};

struct GearCrackPlan {
  std::optional<double> position;  // 0 (fillet top) .. 1 (root circle); empty: the peak
  double length = 0.0, angle = 0.0, increment = 0.0;  // [m], [rad], [m]
  int max_increments = 0;
  std::optional<double> paris_C, paris_m;  // da/dN [m/cycle] = C (dK [MPa m^0.5])^m
  // Lines along which the particles take the crack's spacing: across the
  // tooth's root and down through the rim from the start (body-fitted).
  std::vector<std::vector<geometry::Point>> refine;
};

// Reads and checks /scene/crack against the site (refusals at their
// pointers with the allowed range); `quasi_static`, `fitted`: the job's.
GearCrackPlan plan_gear_crack(const nlohmann::json& crack, const GearCrackSite& site,
                              bool quasi_static, bool fitted);

// The crack's start (at the plan's position or at `peak_arc` along the
// fillet) and its straight initial path from one spacing outside the
// surface; its unit direction in `direction`.
std::vector<geometry::Point> gear_crack_path(const GearCrackPlan& plan, const GearCrackSite& site,
                                             double arc, geometry::Point* direction = nullptr);

// The arc along the tension fillet of a fillet position (0 top, 1 bottom).
double fillet_arc_of_position(const gear::FilletCurve& c, double position);

// Whether the crack, continued straight along its last segment, meets the
// toothed surface within a pitch of tooth 0's axis first (its other flank
// or fillet, or the floor of the space beside it: "tooth"), or the bore or
// the modelled sector's cut sides ("rim").
std::string gear_crack_heading(const std::vector<geometry::Point>& path, const GearCrackSite& site);

// The crack on the scene: cut now (or at the first stage, for the peak),
// grown in stages held `settle_s` each; analysis.crack added to the
// scene's analysis.
void attach_gear_crack(Scene& scene, const GearCrackPlan& plan, std::shared_ptr<GearCrackSite> site,
                       std::shared_ptr<const class RootMonitor> roots, double settle_s);

}  // namespace gearsph::scenes
