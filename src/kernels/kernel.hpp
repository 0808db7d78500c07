#pragma once
// Smoothing kernels W(r, h) with compact support, normalised so that the integral over R^D is 1.
// One class for all kernel types: the type is chosen by name at run time (-kernel), PETSc-style,
// and the per-pair cost of the switch is negligible next to the memory traffic of a pair loop.
//
//   cubic_spline    M4 B-spline (Monaghan & Lattanzio 1985), support 2h
//   quintic_spline  M6 B-spline (Morris 1996), support 3h
//   wendland_c2     Wendland (1995) C2, support 2h; no pairing instability (Dehnen & Aly 2012)
//   wendland_c4     Wendland (1995) C4, support 2h
//   gaussian        Gaussian truncated at 3h, renormalised over its support
#include <string>
#include <vector>

#include "src/core/types.hpp"

namespace sph {

enum class KernelType { CubicSpline, QuinticSpline, WendlandC2, WendlandC4, Gaussian };

const std::vector<std::string>& kernel_names();  // in KernelType order
KernelType kernel_type_from_name(const std::string& name);  // throws sph::Error on unknown names

template <int D> class Kernel {
 public:
  Kernel(KernelType type, double h);

  KernelType type() const { return type_; }
  const std::string& name() const { return kernel_names()[static_cast<int>(type_)]; }
  double h() const { return h_; }
  // Support radius in units of h (kappa), and in length units.
  static double support_factor(KernelType type);
  double support_radius() const { return kappa_ * h_; }

  // Both vanish for r >= support_radius(): tested on r itself, since r/h rounds to just below kappa
  // for some r = kappa h (e.g. h = 0.7), which the truncated Gaussian would turn into W(R) > 0.
  double W(double r) const { return r < support_radius() ? norm_ * shape(r * inv_h_) : 0.0; }
  // dW/dr (negative inside the support).
  double dWdr(double r) const {
    return r < support_radius() ? norm_ * inv_h_ * shape_derivative(r * inv_h_) : 0.0;
  }
  // Gradient with respect to x_i of W(|x_i - x_j|), given r_ij = x_i - x_j and r = |r_ij| > 0.
  Vector<D> gradient(const Vector<D>& rij, double r) const {
    return r > 0.0 ? Vector<D>((dWdr(r) / r) * rij) : Vector<D>(Vector<D>::Zero());
  }

 private:
  double shape(double q) const;             // f(q), W = norm * f(r/h)
  double shape_derivative(double q) const;  // df/dq

  KernelType type_;
  double h_, inv_h_, kappa_, norm_;
};

}  // namespace sph
