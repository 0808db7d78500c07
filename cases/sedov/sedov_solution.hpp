#pragma once
// Self-similar point-explosion solution of Sedov (1959, ch. IV) and Taylor (1950): energy E released at
// t = 0 at the centre of a cold (P = 0) ideal gas of uniform density rho0, in planar (nu = 1),
// cylindrical (nu = 2) or spherical (nu = 3) symmetry. The shock runs at
//   R(t) = xi0 (E t^2 / rho0)^(1/(nu+2)),   Rdot = delta R / t,  delta = 2 / (nu + 2),
// and behind it, with xi = r / R,
//   v = Rdot phi(xi),   rho = rho0 psi(xi),   P = rho0 Rdot^2 pi(xi).
// Substituting into the Euler equations (continuity, momentum, P rho^-gamma constant along paths) gives,
// with a = phi - xi,
//   a psi' + psi (phi' + (nu - 1) phi / xi) = 0,
//   a phi' + pi' / psi = (nu / 2) phi,
//   a (pi'/pi - gamma psi'/psi) = nu,
// from the strong-shock (Rankine-Hugoniot) values phi = pi = 2/(gamma+1), psi = (gamma+1)/(gamma-1) at
// xi = 1 inwards. They are integrated here with RK4 in s = ln xi down to xi = e^-5, where the profile
// has reached its central power laws phi = xi/gamma, psi ~ xi^(nu/(gamma-1)), pi = const (used below
// it), together with the energy integral
//   I = int_0^1 (psi phi^2 / 2 + pi / (gamma - 1)) xi^(nu-1) d xi,
// which fixes xi0 through E = sigma_nu rho0 Rdot^2 R^nu I, i.e. xi0 = (sigma_nu delta^2 I)^(-1/(nu+2)),
// sigma = 2 (a slab: both sides of the plane; Kamm's planar problem counts one), 2 pi, 4 pi. (Kamm & Timmes 2007,
// LA-UR-07-2849, evaluate Sedov's closed-form parametric solution instead; for gamma = 1.4 this integration reproduces
// Kamm's standard problems, R = 1 at t = 1 for the spherical E = 0.851072 and R = 0.75 for the cylindrical E =
// 0.311357, to 3e-8 and 8e-6: xi0 = 1.0040 for nu = 2, 1.0328 for nu = 3; tests/test_sedov.cpp.) Between the grid
// points the profile is interpolated by cubic Hermite polynomials in s with the ODE's own slopes (error ~ ds^4).
#include <array>
#include <vector>

namespace sph {

class SedovSolution {
 public:
  // steps: RK4 steps from the shock (xi = 1) to xi_min = e^-5 (central power laws below).
  SedovSolution(double gamma, int nu, double energy, double rho0, int steps = 20000);

  struct Profile {
    double phi, psi, pi;  // v / Rdot, rho / rho0, P / (rho0 Rdot^2)
  };
  struct State {
    double rho, v, p;  // v: radial velocity
  };

  // Dimensionless profile at xi = r / R in [0, 1] (the shock's inner side at 1).
  Profile profile(double xi) const;
  // Physical state at radius r >= 0 and time t > 0: the profile inside R(t), the cold gas at rest outside.
  State at(double r, double t) const;
  double shock_radius(double t) const;
  double shock_speed(double t) const;
  double post_shock_density() const { return rho0_ * (gamma_ + 1.0) / (gamma_ - 1.0); }

  double xi0() const { return xi0_; }
  double energy_integral() const { return I_; }  // I above
  double gamma() const { return gamma_; }
  int nu() const { return nu_; }
  double energy() const { return E_; }
  double rho0() const { return rho0_; }
  // sigma_nu: the measure of the unit "sphere" (2, 2 pi, 4 pi), E = sigma int (...) r^(nu-1) dr.
  static double geometry_factor(int nu);

 private:
  // y = (phi, ln psi, ln pi, I(xi) = int_xi^1 of the energy integrand); returns dy/ds, s = ln xi.
  using Y = std::array<double, 4>;
  Y rates(double s, const Y& y) const;

  double gamma_, E_, rho0_;
  int nu_;
  double ds_ = 0.0, s_min_ = 0.0, I_ = 0.0, xi0_ = 0.0;
  std::vector<Y> y_, dy_;  // at s_k = -k ds, k = 0..steps
};

}  // namespace sph
