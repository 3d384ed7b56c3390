#pragma once
// The FE check's model read from a rack_pinion job: the pinion the scene
// generates, its material, where it is held (the scene's drive radius), and
// the load tooth 0 carries in a quasi-static run: the rack load per gear as
// a normal force along the line of action at the job's contact point.
#include <string>

#include <nlohmann/json.hpp>

#include "fe/gear_fe_model.hpp"

namespace gearsph::fe {

struct GearFeJob {
  GearFeCase model;             // loaded with the nominal force at the contact point
  std::string name;             // the job's
  std::string contact_point;    // as the job names it: "pitch", ..., or "24.5 mm"
  double rack_load_N = 0.0;     // per gear: the tangential force F_t
  double pressure_angle = 0.0;  // [rad]
  double rim_depth_m = 0.0;
  double module_m = 0.0;
};

// `job` is validated with defaults filled in (validate_job). Throws
// InvalidJob (with the field's pointer) for a job the check cannot model:
// another scene, not quasi-static, no load, a contact point off the flank.
GearFeJob read_gear_fe_job(const nlohmann::json& job);

// The radius of a contact point on the pinion: a named point of the path
// of contact or a radius in mm.
double contact_radius(const geometry::PinionGeometry& pinion, const nlohmann::json& contact_point);

}  // namespace gearsph::fe
