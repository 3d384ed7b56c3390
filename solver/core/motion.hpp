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
    Rotation,  // rigid rotation about (cx, cy) at omega (counter-clockwise positive)
    GuidedX,   // v_y = 0, x free (a particle on a horizontal guide)
  };
  Kind kind = Kind::Free;
  std::string name = "free";
  double vx = 0.0, vy = 0.0;  // Velocity
  double cx = 0.0, cy = 0.0;  // Rotation centre [m]
  double omega = 0.0;         // Rotation rate [rad/s]

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
  static Motion guided_x(std::string n) { return {Kind::GuidedX, std::move(n)}; }

  bool integrates_x() const { return kind == Kind::Free || kind == Kind::GuidedX; }
  bool integrates_y() const { return kind == Kind::Free; }
};

}  // namespace gearsph
