#pragma once
// Exact solution of the Riemann problem of the 1D Euler equations for an ideal gas (Toro 2009,
// "Riemann Solvers and Numerical Methods for Fluid Dynamics", 3rd ed., ch. 4): the star pressure p*
// from Newton's iteration on f(p) = f_L(p) + f_R(p) + (u_R - u_L) = 0 (sec. 4.3), the star velocity
// u* = (u_L + u_R)/2 + (f_R(p*) - f_L(p*))/2, and the similarity solution W(x/t) sampled as in sec. 4.5.
// Independent of the SPH code: it is the reference the Sod case's errors are measured against.
namespace sph {

struct GasState {
  double rho = 1.0, u = 0.0, p = 1.0;
};

class ExactRiemann {
 public:
  // Solves for the star region; throws sph::Error when the data generate vacuum (Toro eq. 4.82).
  ExactRiemann(const GasState& left, const GasState& right, double gamma);

  double p_star() const { return p_star_; }
  double u_star() const { return u_star_; }
  double rho_star_left() const { return rho_star_L_; }
  double rho_star_right() const { return rho_star_R_; }
  bool left_is_shock() const { return p_star_ > L_.p; }
  bool right_is_shock() const { return p_star_ > R_.p; }
  // Wave speeds: a shock's speed, or a rarefaction's head (fastest outward) and tail.
  double left_head_speed() const;
  double left_tail_speed() const;
  double right_head_speed() const;
  double right_tail_speed() const;
  int iterations() const { return iterations_; }

  // The solution at similarity coordinate s = x / t (interface at x = 0 at t = 0).
  GasState sample(double s) const;
  // The solution at (x, t) for an interface at x0; t <= 0 gives the initial data.
  GasState at(double x, double t, double x0 = 0.0) const;

 private:
  // f_K(p) and its derivative for side K (Toro eqs. 4.6, 4.7, 4.37).
  void pressure_function(double p, const GasState& K, double cK, double& f, double& df) const;

  GasState L_, R_;
  double gamma_, cL_, cR_;
  double p_star_ = 0.0, u_star_ = 0.0, rho_star_L_ = 0.0, rho_star_R_ = 0.0;
  int iterations_ = 0;
};

}  // namespace sph
