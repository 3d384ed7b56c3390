#pragma once
// One interface over the four smoothing kernels. A kernel is a shape f(q),
// q = r/h, with compact support `support * h`, scaled to unit integral:
// W(r) = norm_2d / h^2 * f(r/h). Hot loops are instantiated per kernel type
// through `with_kernel`, so the shape functions inline.
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>

#include "solver/kernels/cubic_spline.hpp"
#include "solver/kernels/quintic_spline.hpp"
#include "solver/kernels/seed_quartic.hpp"
#include "solver/kernels/wendland_c2.hpp"

namespace gearsph {

enum class KernelType { SeedQuartic, CubicSpline, QuinticSpline, WendlandC2 };

std::optional<KernelType> kernel_from_name(std::string_view name);
const char* kernel_name(KernelType type);
double kernel_support(KernelType type);  // in units of h

// A kernel of one type at one smoothing length, in 2D.
template <class Shape>
struct Kernel2D {
  using shape_type = Shape;
  double h;
  double inv_h;
  double norm;  // norm_2d / h^2
  double radius;

  explicit Kernel2D(double h_)
      : h(h_), inv_h(1.0 / h_), norm(Shape::norm_2d / (h_ * h_)), radius(Shape::support * h_) {}

  double W(double r) const { return norm * Shape::shape(r * inv_h); }
  // dW/dr
  double dW(double r) const { return norm * inv_h * Shape::shape_derivative(r * inv_h); }
  // The same shape at another smoothing length: a pair of graded particles
  // takes h_ij = (h_i + h_j) / 2, symmetric, so grad_i W_ij = -grad_j W_ji.
  static double W_at(double r, double h) { return Shape::norm_2d / (h * h) * Shape::shape(r / h); }
  static double dW_at(double r, double h) {
    return Shape::norm_2d / (h * h * h) * Shape::shape_derivative(r / h);
  }
};

// Calls fn(Kernel2D<Shape>{h}) with the shape of `type`.
template <class Fn>
decltype(auto) with_kernel(KernelType type, double h, Fn&& fn) {
  switch (type) {
    case KernelType::SeedQuartic:
      return fn(Kernel2D<kernels::SeedQuartic>(h));
    case KernelType::CubicSpline:
      return fn(Kernel2D<kernels::CubicSpline>(h));
    case KernelType::QuinticSpline:
      return fn(Kernel2D<kernels::QuinticSpline>(h));
    case KernelType::WendlandC2:
      break;
  }
  return fn(Kernel2D<kernels::WendlandC2>(h));
}

}  // namespace gearsph
