#pragma once
// Kinematic constraints on particle groups. Every particle carries a motion
// index; index 0 is "free" (integrated from its acceleration). The others
// prescribe the velocity (and, where exact, the position) of their members.
#include <string>

namespace gearsph {

struct Motion {
  enum class Kind {
    Free,      // integrated from forces
    Fixed,     // v = 0, x = x0
    Velocity,  // v = (vx, vy), x = x0 + v t
    Rotation,  // rigid rotation about (cx, cy) at omega (counter-clockwise positive),
               // held or, torque_driven, following the group's torque balance
    GuidedX,   // v_y = 0, x free (a particle on a horizontal guide)
  };
  Kind kind = Kind::Free;
  std::string name = "free";
  double vx = 0.0, vy = 0.0;  // Velocity
  double cx = 0.0, cy = 0.0;  // Rotation centre [m]
  double omega = 0.0;         // Rotation rate [rad/s]; the initial one when torque-driven
  double angle = 0.0;         // Rotation: turned since t = 0 [rad]
  // cos and sin of the angle at the end of the step being taken, set once
  // per group by the opening kick and by the drift (not once per particle).
  double cos_next = 1.0, sin_next = 0.0;
  // A torque-driven rotation is a rigid body: omega and angle are state,
  // advanced from I dω/dt = T + the moment of the forces on the group
  // (integrate/motion.cpp). Per unit thickness, like the particles' masses.
  bool torque_driven = false;
  double torque = 0.0;            // applied at full load ramp [N m / m]
  double attached_inertia = 0.0;  // rigidly attached but not modelled [kg m^2 / m]
  double group_inertia = 0.0;     // of the group's particles about (cx, cy) [kg m^2 / m]
  double alpha = 0.0;             // angular acceleration at the last kick [rad/s^2]
  // GuidedX: the x inertia of each member over its own mass, 1 + (attached
  // mass) / (the group's mass): a mass that moves with the guided group but
  // is not modelled (the rack bar beyond the segment), shared in proportion
  // to the members' masses.
  double inertia_scale = 1.0;

  static Motion free() { return {}; }
  static Motion fixed(std::string n) { return {Kind::Fixed, std::move(n)}; }
  static Motion velocity(std::string n, double vx, double vy) {
    Motion m{Kind::Velocity, std::move(n)};
    m.vx = vx;
    m.vy = vy;
    return m;
  }
  static Motion rotation(std::string n, double cx, double cy, double omega) {
    Motion m{Kind::Rotation, std::move(n)};
    m.cx = cx;
    m.cy = cy;
    m.omega = omega;
    return m;
  }
  static Motion torque_rotation(std::string n, double cx, double cy, double omega0, double torque,
                                double attached_inertia) {
    Motion m = rotation(std::move(n), cx, cy, omega0);
    m.torque_driven = true;
    m.torque = torque;
    m.attached_inertia = attached_inertia;
    return m;
  }
  static Motion guided_x(std::string n) { return {Kind::GuidedX, std::move(n)}; }

  bool integrates_x() const { return kind == Kind::Free || kind == Kind::GuidedX; }
  bool integrates_y() const { return kind == Kind::Free; }
};

}  // namespace gearsph
