#pragma once
// The error of a run that blew up, below the integrator that throws it and
// the guard and health checks that find it.
#include <stdexcept>
#include <string>
#include <utility>

namespace gearsph {

// A run that blew up: which step, which particle, which quantity.
class DivergenceError : public std::runtime_error {
 public:
  DivergenceError(std::string message, long at_step, long at_particle, std::string what,
                  double bad_value)
      : std::runtime_error(std::move(message)),
        step(at_step),
        particle(at_particle),
        quantity(std::move(what)),
        value(bad_value) {}
  long step;
  long particle;
  std::string quantity;
  double value;
};

}  // namespace gearsph
