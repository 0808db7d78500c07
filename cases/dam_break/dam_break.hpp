#pragma once
// Dam break (Martin & Moyce 1952; Koshizuka & Oka 1996): a water column of width a and height 2a at
// rest against the left wall of a tank 4a long collapses under gravity. Free surface, walls on the
// left, right and bottom. Reference: the experimental surge-front positions Z = x/a against
// T = t sqrt(2g/a) (cases/dam_break/data/); error front_position_rel = mean |Z - Z_exp| / Z_exp over
// the experimental points reached so far, before the front meets the far wall (Z < 4). Also recorded:
// the pressure at the foot of the left wall, the probe where ISPH and WCSPH differ most, at the foot of
// the far wall (the surge's impact), and the column's height at the left wall (front_position.csv).
// In 3D (-dim 3) the column is a x 2a x a in a tank 4a long and a deep, with walls in front and behind:
// the same front, with the friction of those walls added.
#include <vector>

#include "src/run/case.hpp"

namespace sph {

template <int D> class DamBreak : public Case<D> {
 public:
  std::string name() const override { return "dam_break"; }
  void set_from_options() override;
  void create(Particles<D>& P, Domain<D>& domain) const override;
  double spacing() const override { return a_ / nx_; }
  double minimum_particles() const override { return D == 3 ? 2.0 * nx_ * nx_ * nx_ : 2.0 * nx_ * nx_; }  // the column
  int resolution() const override { return nx_; }
  Physics<D> physics() const override;
  double default_t_end() const override;  // T = 3
  double wall_thickness() const override { return wall_layers_ * spacing(); }
  std::map<std::string, double> errors(const Particles<D>& P, double t) const override;
  std::string unmeasured_reason(const std::string& name) const override;
  void write_outputs(const Particles<D>& P, double t, const std::string& dir) const override;
  nlohmann::json parameters() const override;

 private:
  double front(const Particles<D>& P) const;  // surge-front position x
  double foot_pressure(const Particles<D>& P, double x0) const;
  double column_height(const Particles<D>& P) const;
  double time_scale() const;  // sqrt(a / (2 g)): T = t / time_scale

  PetscInt nx_ = 20, wall_layers_ = 4;
  PetscReal a_ = 1.0, g_ = 1.0, re_ = 1000.0, rho0_ = 1.0;
  struct Record {
    double T, Z, P, P_far, H;  // time, front position, foot pressures / (rho0 g a) left and far, column height / a
  };
  mutable std::vector<Record> history_;    // as the run advances
  mutable double first_measured_T_ = 0.0;  // earliest experimental point used
};

}  // namespace sph
