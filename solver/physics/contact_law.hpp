#pragma once
// The choice among the contact laws (contact.hpp), made in one place: the
// pair loop (contact_pairs.cpp) and the time-step bound (contact.cpp) both
// switch on contact_law(config).
#include "solver/core/material.hpp"
#include "solver/physics/contact.hpp"

namespace gearsph::physics {

enum class ContactLaw {
  Seed,       // the seed paper's linear penalty (contact_seed_penalty.hpp)
  Hertz,      // overlap^(3/2) (contact_hertz.hpp)
  NearField,  // the surface model's continuum compliance (contact_near_field.hpp)
};

inline ContactLaw contact_law(const ContactConfig& config) {
  if (config.model == ContactModel::Hertz) return ContactLaw::Hertz;
  if (config.model == ContactModel::Surface && config.near_field) return ContactLaw::NearField;
  return ContactLaw::Seed;
}

// Plane-strain contact modulus of two materials (Johnson 1985, eq. 4.23 form).
inline double contact_modulus(const Material& a, const Material& b) {
  return 1.0 / ((1.0 - a.nu * a.nu) / a.E + (1.0 - b.nu * b.nu) / b.E);
}

// K = 2 (1 - nu^2) / (pi E) of a half-plane (contact_near_field.hpp).
inline double plane_strain_compliance(const Material& m) {
  return 2.0 * (1.0 - m.nu * m.nu) / (3.141592653589793 * m.E);
}

}  // namespace gearsph::physics
