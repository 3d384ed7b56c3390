#include "solver/kernels/kernel.hpp"

namespace gearsph {

std::optional<KernelType> kernel_from_name(std::string_view name) {
  for (KernelType t : {KernelType::SeedQuartic, KernelType::CubicSpline, KernelType::QuinticSpline,
                       KernelType::WendlandC2}) {
    if (name == kernel_name(t)) return t;
  }
  return std::nullopt;
}

const char* kernel_name(KernelType type) {
  return with_kernel(
      type, 1.0, [](const auto& k) { return std::remove_cvref_t<decltype(k)>::shape_type::name; });
}

double kernel_support(KernelType type) {
  return with_kernel(type, 1.0, [](const auto& k) { return k.radius; });
}

}  // namespace gearsph
