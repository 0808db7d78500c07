#include "src/kernels/kernel.hpp"

#include <cmath>

#include "src/core/error.hpp"

namespace sph {

const std::vector<std::string>& kernel_names() {
  static const std::vector<std::string> names = {"cubic_spline", "quintic_spline", "wendland_c2", "wendland_c4",
                                                 "gaussian"};
  return names;
}

KernelType kernel_type_from_name(const std::string& name) {
  const auto& names = kernel_names();
  for (std::size_t k = 0; k < names.size(); ++k)
    if (names[k] == name) return static_cast<KernelType>(k);
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
  throw Error("unknown kernel '" + name + "'; choose -kernel from: " + list);
}

namespace {
constexpr double pi = M_PI;

// Normalisation constant sigma_D of f(q) so that sigma/h^D * f integrates to one in D dimensions.
double sigma(KernelType t, int D) {
  switch (t) {
    case KernelType::CubicSpline: return D == 1 ? 2.0 / 3.0 : D == 2 ? 10.0 / (7.0 * pi) : 1.0 / pi;
    case KernelType::QuinticSpline: return D == 1 ? 1.0 / 120.0 : D == 2 ? 7.0 / (478.0 * pi) : 1.0 / (120.0 * pi);
    // Wendland functions of s = q/2 on [0, 1]; the 1D kernels are the psi_{1,k} family.
    case KernelType::WendlandC2: return D == 1 ? 5.0 / 8.0 : D == 2 ? 7.0 / (4.0 * pi) : 21.0 / (16.0 * pi);
    case KernelType::WendlandC4: return D == 1 ? 3.0 / 4.0 : D == 2 ? 9.0 / (4.0 * pi) : 495.0 / (256.0 * pi);
    case KernelType::Gaussian: {
      // exp(-q^2) integrated over the truncated ball q < 3.
      const double R = detail::kernel_gaussian_cut, e = std::exp(-R * R);
      const double integral = D == 1   ? std::sqrt(pi) * std::erf(R)
                              : D == 2 ? pi * (1.0 - e)
                                       : std::pow(pi, 1.5) * std::erf(R) - 2.0 * pi * R * e;
      return 1.0 / integral;
    }
  }
  return 0.0;
}

}  // namespace

template <int D> double Kernel<D>::default_eta(KernelType t) {
  switch (t) {
    case KernelType::CubicSpline: return 1.2;
    case KernelType::QuinticSpline: return 1.0;
    case KernelType::WendlandC2: return 1.3;
    case KernelType::WendlandC4: return 1.5;
    case KernelType::Gaussian: return 1.0;
  }
  return 1.2;
}

template <int D> double Kernel<D>::support_factor(KernelType t) {
  return (t == KernelType::QuinticSpline || t == KernelType::Gaussian) ? 3.0 : 2.0;
}

template <int D> Kernel<D>::Kernel(KernelType type, double h)
    : type_(type), h_(h), inv_h_(1.0 / h), kappa_(support_factor(type)), norm_(sigma(type, D) / std::pow(h, D)) {
  if (!(h > 0.0)) throw Error("smoothing length must be positive (got " + std::to_string(h) + ")");
}

template class Kernel<1>;
template class Kernel<2>;
template class Kernel<3>;

}  // namespace sph
