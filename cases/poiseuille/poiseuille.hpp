#pragma once
// Body-force-driven channel flow between fixed walls at y = 0 and y = L = 1, periodic in x, started
// from rest (Morris, Fox & Zhu 1997). Reference: the transient series solution
//   u(y,t) = F/(2 nu) y (L - y)
//          - sum_n 4 F L^2 / (nu pi^3 (2n+1)^3) sin((2n+1) pi y / L) exp(-(2n+1)^2 pi^2 nu t / L^2),
// whose steady centreline speed is U = F L^2 / (8 nu); Re = U L / nu.
#include "src/run/case.hpp"

namespace sph {

class Poiseuille : public Case<2> {
 public:
  std::string name() const override { return "poiseuille"; }
  void set_from_options() override;
  void create(Particles<2>& P, Domain<2>& domain) const override;
  double spacing() const override { return 1.0 / ny_; }
  double minimum_particles() const override { return 12.0 * ny_; }
  int resolution() const override { return ny_; }
  Physics<2> physics() const override;
  double default_t_end() const override { return 1.0; }
  double wall_thickness() const override { return wall_layers_ * spacing(); }
  std::map<std::string, double> errors(const Particles<2>& P, double t) const override;
  nlohmann::json parameters() const override;

  double velocity(double y, double t) const;  // the series solution (public for tests)

 private:
  PetscInt ny_ = 40, wall_layers_ = 4;
  PetscReal re_ = 10.0, U_ = 1.0, rho0_ = 1.0;
  double nu() const { return U_ / re_; }
  double force() const { return 8.0 * nu() * U_; }  // F with F L^2 / (8 nu) = U, L = 1
};

}  // namespace sph
