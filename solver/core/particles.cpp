#include "solver/core/particles.hpp"

#include <cmath>
#include <limits>

namespace gearsph {

void Particles::resize(std::size_t count) {
  n = count;
  body.resize(count, 0);
  motion.resize(count, 0);
  correction_order.resize(count, 0);
  surf_depth.resize(count, std::numeric_limits<double>::infinity());
  for (auto* v : {&spacing,    &x0,         &y0,      &mass,    &rho0,    &cs,
                  &x,          &y,          &vx,      &vy,      &rho,     &p,
                  &sxx,        &syy,        &sxy,     &szz,     &ax,      &ay,
                  &drho,       &lxx,        &lxy,     &lyx,     &lyy,     &bxx,
                  &bxy,        &byx,        &byy,     &fxx,     &fxy,     &fyx,
                  &fyy,        &rxx,        &ryy,     &rxy,     &qxx,     &qxy,
                  &qyx,        &qyy,        &ext_ax,  &ext_ay,  &load_ax, &load_ay,
                  &contact_ax, &contact_ay, &surf_nx, &surf_ny, &rot,     &bqx0,
                  &bqx1,       &bqx2,       &bqy0,    &bqy1,    &bqy2,    &qqx0,
                  &qqx1,       &qqx2,       &qqy0,    &qqy1,    &qqy2,    &surf_curvature}) {
    v->resize(count, 0.0);
  }
  surf_curvature_rate.resize(count, 0.0);
  surf_hertz_curvature.resize(count, 0.0);
}

void Particles::release_updated_lagrangian() {
  for (auto* v : {&drho, &lxx,  &lxy,  &lyx,  &lyy,  &bxx,  &bxy,  &byx,  &byy, &bqx0,
                  &bqx1, &bqx2, &bqy0, &bqy1, &bqy2, &rxx,  &ryy,  &rxy,  &qxx, &qxy,
                  &qyx,  &qyy,  &qqx0, &qqx1, &qqx2, &qqy0, &qqy1, &qqy2, &rot}) {
    Column<double>().swap(*v);
  }
}

void Particles::add(double px, double py, double m, double density, int body_index,
                    int motion_index, double particle_spacing) {
  const std::size_t i = n;
  resize(n + 1);
  spacing[i] = particle_spacing;
  body[i] = body_index;
  motion[i] = static_cast<std::uint16_t>(motion_index);
  x0[i] = x[i] = px;
  y0[i] = y[i] = py;
  mass[i] = m;
  rho0[i] = rho[i] = density;
  bxx[i] = byy[i] = 1.0;
  fxx[i] = fyy[i] = 1.0;
}

double Particles::von_mises(std::size_t i) const {
  return std::sqrt(3.0 * j2(i));
}

}  // namespace gearsph
