#pragma once
// Smoothing kernels W(r, h) with compact support, normalised so that the integral over R^D is 1.
// One class for all kernel types: the type is chosen by name at run time (-kernel), PETSc-style,
// and the per-pair cost of the switch is small once the shape functions are inlined (below).
//
//   cubic_spline    M4 B-spline (Monaghan & Lattanzio 1985), support 2h
//   quintic_spline  M6 B-spline (Morris 1996), support 3h
//   wendland_c2     Wendland (1995) C2, support 2h; no pairing instability (Dehnen & Aly 2012)
//   wendland_c4     Wendland (1995) C4, support 2h
//   gaussian        Gaussian truncated at 3h, renormalised over its support
#include <cmath>
#include <string>
#include <vector>

#include "src/core/types.hpp"

namespace sph {

enum class KernelType { CubicSpline, QuinticSpline, WendlandC2, WendlandC4, Gaussian };

const std::vector<std::string>& kernel_names();             // in KernelType order
KernelType kernel_type_from_name(const std::string& name);  // throws sph::Error on unknown names

template <int D> class Kernel {
 public:
  Kernel(KernelType type, double h);

  KernelType type() const { return type_; }
  const std::string& name() const { return kernel_names()[static_cast<int>(type_)]; }
  double h() const { return h_; }
  // Support radius in units of h (kappa), and in length units.
  static double support_factor(KernelType type);
  // eta in h = eta (m / rho)^(1/D) for variable smoothing lengths: about 1.2 for the cubic spline (Price
  // 2012 sec. 3.2), fewer smoothing lengths for the kernels with support 3h, more for the Wendland
  // kernels, which need more neighbours (Dehnen & Aly 2012).
  static double default_eta(KernelType type);
  double support_radius() const { return kappa_ * h_; }

  // Both vanish for r >= support_radius(): tested on r itself, since r/h rounds to just below kappa
  // for some r = kappa h (e.g. h = 0.7), which the truncated Gaussian would turn into W(R) > 0.
  double W(double r) const { return r < support_radius() ? norm_ * shape(r * inv_h_) : 0.0; }
  // dW/dr (negative inside the support).
  double dWdr(double r) const { return r < support_radius() ? norm_ * inv_h_ * shape_derivative(r * inv_h_) : 0.0; }
  // W[k] = W(r[k]) and dWdr[k] = dW/dr(r[k]) for k < n, the same values as W() and dWdr(): the type's
  // switch is taken once for all n, so the loop over k has no branches the compiler cannot vectorise.
  void evaluate(std::size_t n, const double* r, double* W, double* dWdr) const;
  // Gradient with respect to x_i of W(|x_i - x_j|), given r_ij = x_i - x_j and r = |r_ij| > 0.
  Vector<D> gradient(const Vector<D>& rij, double r) const {
    return r > 0.0 ? Vector<D>((dWdr(r) / r) * rij) : Vector<D>(Vector<D>::Zero());
  }

 private:
  double shape(double q) const;             // f(q), W = norm * f(r/h)
  double shape_derivative(double q) const;  // df/dq
  template <KernelType T> void evaluate_as(std::size_t n, const double* r, double* W, double* dWdr) const;

  KernelType type_;
  double h_, inv_h_, kappa_, norm_;
};

// The shape functions are defined here, not in kernel.cpp, so that the pair loops inline them: out of
// line the calls are a tenth of a step (docs/performance.md, "Design measurements").
namespace detail {
constexpr double kernel_gaussian_cut = 3.0;
inline double kernel_pos(double x) { return x > 0.0 ? x : 0.0; }
inline double kernel_pow4(double x) { return (x * x) * (x * x); }
}  // namespace detail

namespace detail {
// f(q) and df/dq of each type, one function per type so that a loop over one type has no switch.
template <KernelType T, int D> inline double kernel_shape(double q) {
  if constexpr (T == KernelType::CubicSpline) {
    if (q < 1.0) return 1.0 - 1.5 * q * q + 0.75 * q * q * q;
    if (q < 2.0) return 0.25 * std::pow(2.0 - q, 3);
    return 0.0;
  } else if constexpr (T == KernelType::QuinticSpline) {
    if (q >= 3.0) return 0.0;
    const double a = kernel_pos(3.0 - q), b = kernel_pos(2.0 - q), c = kernel_pos(1.0 - q);
    return a * kernel_pow4(a) - 6.0 * b * kernel_pow4(b) + 15.0 * c * kernel_pow4(c);
  } else if constexpr (T == KernelType::WendlandC2) {  // selects, not branches: the loops vectorise
    const double s = 0.5 * q, t = 1.0 - s;
    const double f = D == 1 ? t * t * t * (1.0 + 3.0 * s) : kernel_pow4(t) * (1.0 + 4.0 * s);
    return q >= 2.0 ? 0.0 : f;
  } else if constexpr (T == KernelType::WendlandC4) {
    const double s = 0.5 * q, t = 1.0 - s;
    const double f = D == 1 ? t * kernel_pow4(t) * (1.0 + 5.0 * s + 8.0 * s * s)
                            : kernel_pow4(t) * t * t * (1.0 + 6.0 * s + 35.0 / 3.0 * s * s);
    return q >= 2.0 ? 0.0 : f;
  } else {
    return q < kernel_gaussian_cut ? std::exp(-q * q) : 0.0;
  }
}

template <KernelType T, int D> inline double kernel_shape_derivative(double q) {
  if constexpr (T == KernelType::CubicSpline) {
    if (q < 1.0) return -3.0 * q + 2.25 * q * q;
    if (q < 2.0) return -0.75 * (2.0 - q) * (2.0 - q);
    return 0.0;
  } else if constexpr (T == KernelType::QuinticSpline) {
    if (q >= 3.0) return 0.0;
    const double a = kernel_pos(3.0 - q), b = kernel_pos(2.0 - q), c = kernel_pos(1.0 - q);
    return -5.0 * kernel_pow4(a) + 30.0 * kernel_pow4(b) - 75.0 * kernel_pow4(c);
  } else if constexpr (T == KernelType::WendlandC2) {  // d/dq = (1/2) d/ds for the Wendland functions of s = q/2
    const double s = 0.5 * q, t = 1.0 - s;
    const double f = D == 1 ? -6.0 * s * t * t : -10.0 * s * t * t * t;
    return q >= 2.0 ? 0.0 : f;
  } else if constexpr (T == KernelType::WendlandC4) {
    const double s = 0.5 * q, t = 1.0 - s;
    const double f =
        D == 1 ? -7.0 * s * (1.0 + 4.0 * s) * kernel_pow4(t) : -28.0 / 3.0 * s * (1.0 + 5.0 * s) * kernel_pow4(t) * t;
    return q >= 2.0 ? 0.0 : f;
  } else {
    return q < kernel_gaussian_cut ? -2.0 * q * std::exp(-q * q) : 0.0;
  }
}
}  // namespace detail

template <int D> inline double Kernel<D>::shape(double q) const {
  switch (type_) {
    case KernelType::CubicSpline: return detail::kernel_shape<KernelType::CubicSpline, D>(q);
    case KernelType::QuinticSpline: return detail::kernel_shape<KernelType::QuinticSpline, D>(q);
    case KernelType::WendlandC2: return detail::kernel_shape<KernelType::WendlandC2, D>(q);
    case KernelType::WendlandC4: return detail::kernel_shape<KernelType::WendlandC4, D>(q);
    case KernelType::Gaussian: return detail::kernel_shape<KernelType::Gaussian, D>(q);
  }
  return 0.0;
}

template <int D> inline double Kernel<D>::shape_derivative(double q) const {
  switch (type_) {
    case KernelType::CubicSpline: return detail::kernel_shape_derivative<KernelType::CubicSpline, D>(q);
    case KernelType::QuinticSpline: return detail::kernel_shape_derivative<KernelType::QuinticSpline, D>(q);
    case KernelType::WendlandC2: return detail::kernel_shape_derivative<KernelType::WendlandC2, D>(q);
    case KernelType::WendlandC4: return detail::kernel_shape_derivative<KernelType::WendlandC4, D>(q);
    case KernelType::Gaussian: return detail::kernel_shape_derivative<KernelType::Gaussian, D>(q);
  }
  return 0.0;
}

template <int D> template <KernelType T>
inline void Kernel<D>::evaluate_as(std::size_t n, const double* r, double* W, double* dWdr) const {
  const double R = support_radius(), inv_h = inv_h_, norm = norm_, norm_dq = norm_ * inv_h_;
  for (std::size_t k = 0; k < n; ++k) {
    const double q = r[k] * inv_h;
    const double w = norm * detail::kernel_shape<T, D>(q), dw = norm_dq * detail::kernel_shape_derivative<T, D>(q);
    W[k] = r[k] < R ? w : 0.0;
    dWdr[k] = r[k] < R ? dw : 0.0;
  }
}

template <int D> inline void Kernel<D>::evaluate(std::size_t n, const double* r, double* W, double* dWdr) const {
  switch (type_) {
    case KernelType::CubicSpline: return evaluate_as<KernelType::CubicSpline>(n, r, W, dWdr);
    case KernelType::QuinticSpline: return evaluate_as<KernelType::QuinticSpline>(n, r, W, dWdr);
    case KernelType::WendlandC2: return evaluate_as<KernelType::WendlandC2>(n, r, W, dWdr);
    case KernelType::WendlandC4: return evaluate_as<KernelType::WendlandC4>(n, r, W, dWdr);
    case KernelType::Gaussian: return evaluate_as<KernelType::Gaussian>(n, r, W, dWdr);
  }
}

// The kernel sum of a square (cubic) lattice of spacing dx about one of its points, sum_k dx^D W(|k| dx)
// (self included): what a particle's number density reads, in volumes, where the particles lie on one.
// Near 1, not 1: the sum's error on a lattice.
template <int D> double lattice_kernel_sum(const Kernel<D>& K, double dx) {
  const int n = static_cast<int>(std::ceil(K.support_radius() / dx));
  double sum = 0.0;
  for (int a = -n; a <= n; ++a)
    for (int b = -n; b <= n; ++b)
      for (int c = D == 3 ? -n : 0; c <= (D == 3 ? n : 0); ++c) {
        const double r2 = D == 1 ? double(a * a) : D == 2 ? double(a * a + b * b) : double(a * a + b * b + c * c);
        if (D == 1 && b != 0) continue;
        sum += K.W(std::sqrt(r2) * dx);
      }
  return sum * std::pow(dx, D);
}

}  // namespace sph
