#include "src/kernels/kernel.hpp"

#include <cmath>

#include "src/core/error.hpp"

namespace sph {

const std::vector<std::string>& kernel_names() {
  static const std::vector<std::string> names = {"cubic_spline", "quintic_spline", "wendland_c2",
                                                 "wendland_c4", "gaussian"};
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
constexpr double gaussian_cut = 3.0;

// Normalisation constant sigma_D of f(q) so that sigma/h^D * f integrates to one in D dimensions.
double sigma(KernelType t, int D) {
  switch (t) {
    case KernelType::CubicSpline: return D == 1 ? 2.0 / 3.0 : D == 2 ? 10.0 / (7.0 * pi) : 1.0 / pi;
    case KernelType::QuinticSpline:
      return D == 1 ? 1.0 / 120.0 : D == 2 ? 7.0 / (478.0 * pi) : 1.0 / (120.0 * pi);
    // Wendland functions of s = q/2 on [0, 1]; the 1D kernels are the psi_{1,k} family.
    case KernelType::WendlandC2: return D == 1 ? 5.0 / 8.0 : D == 2 ? 7.0 / (4.0 * pi) : 21.0 / (16.0 * pi);
    case KernelType::WendlandC4: return D == 1 ? 3.0 / 4.0 : D == 2 ? 9.0 / (4.0 * pi) : 495.0 / (256.0 * pi);
    case KernelType::Gaussian: {
      // exp(-q^2) integrated over the truncated ball q < 3.
      const double R = gaussian_cut, e = std::exp(-R * R);
      const double integral = D == 1   ? std::sqrt(pi) * std::erf(R)
                              : D == 2 ? pi * (1.0 - e)
                                       : std::pow(pi, 1.5) * std::erf(R) - 2.0 * pi * R * e;
      return 1.0 / integral;
    }
  }
  return 0.0;
}

inline double pos(double x) { return x > 0.0 ? x : 0.0; }
inline double pow4(double x) { return (x * x) * (x * x); }
}  // namespace

template <int D> double Kernel<D>::support_factor(KernelType t) {
  return (t == KernelType::QuinticSpline || t == KernelType::Gaussian) ? 3.0 : 2.0;
}

template <int D>
Kernel<D>::Kernel(KernelType type, double h)
    : type_(type), h_(h), inv_h_(1.0 / h), kappa_(support_factor(type)),
      norm_(sigma(type, D) / std::pow(h, D)) {
  if (!(h > 0.0)) throw Error("smoothing length must be positive (got " + std::to_string(h) + ")");
}

template <int D> double Kernel<D>::shape(double q) const {
  switch (type_) {
    case KernelType::CubicSpline:
      if (q < 1.0) return 1.0 - 1.5 * q * q + 0.75 * q * q * q;
      if (q < 2.0) return 0.25 * std::pow(2.0 - q, 3);
      return 0.0;
    case KernelType::QuinticSpline: {
      if (q >= 3.0) return 0.0;
      const double a = pos(3.0 - q), b = pos(2.0 - q), c = pos(1.0 - q);
      return a * pow4(a) - 6.0 * b * pow4(b) + 15.0 * c * pow4(c);
    }
    case KernelType::WendlandC2: {
      if (q >= 2.0) return 0.0;
      const double s = 0.5 * q, t = 1.0 - s;
      return D == 1 ? t * t * t * (1.0 + 3.0 * s) : pow4(t) * (1.0 + 4.0 * s);
    }
    case KernelType::WendlandC4: {
      if (q >= 2.0) return 0.0;
      const double s = 0.5 * q, t = 1.0 - s;
      return D == 1 ? t * pow4(t) * (1.0 + 5.0 * s + 8.0 * s * s)
                    : pow4(t) * t * t * (1.0 + 6.0 * s + 35.0 / 3.0 * s * s);
    }
    case KernelType::Gaussian: return q < gaussian_cut ? std::exp(-q * q) : 0.0;
  }
  return 0.0;
}

template <int D> double Kernel<D>::shape_derivative(double q) const {
  switch (type_) {
    case KernelType::CubicSpline:
      if (q < 1.0) return -3.0 * q + 2.25 * q * q;
      if (q < 2.0) return -0.75 * (2.0 - q) * (2.0 - q);
      return 0.0;
    case KernelType::QuinticSpline: {
      if (q >= 3.0) return 0.0;
      const double a = pos(3.0 - q), b = pos(2.0 - q), c = pos(1.0 - q);
      return -5.0 * pow4(a) + 30.0 * pow4(b) - 75.0 * pow4(c);
    }
    // d/dq = (1/2) d/ds for the Wendland functions of s = q/2.
    case KernelType::WendlandC2: {
      if (q >= 2.0) return 0.0;
      const double s = 0.5 * q, t = 1.0 - s;
      return D == 1 ? -6.0 * s * t * t : -10.0 * s * t * t * t;
    }
    case KernelType::WendlandC4: {
      if (q >= 2.0) return 0.0;
      const double s = 0.5 * q, t = 1.0 - s;
      return D == 1 ? -7.0 * s * (1.0 + 4.0 * s) * pow4(t)
                    : -28.0 / 3.0 * s * (1.0 + 5.0 * s) * pow4(t) * t;
    }
    case KernelType::Gaussian: return q < gaussian_cut ? -2.0 * q * std::exp(-q * q) : 0.0;
  }
  return 0.0;
}

template class Kernel<1>;
template class Kernel<2>;
template class Kernel<3>;

}  // namespace sph
