#pragma once
// Still water: a tank of width L holding water of depth H at rest under gravity, walls on the floor and
// both sides, open at the top, started with its hydrostatic pressure. Nothing should move: the
// reference is the state it starts in. Errors (fluid particles, all ranks):
//   hydrostatic_l1_rel  mean |p - rho0 g (H - y)| / (rho0 g H), against the exact hydrostatic pressure
//                       of the particle's current height under the start's level H;
//   max_drift_dx        the largest distance a particle has moved from its start, in spacings;
//   level_rel           the mean height of the particles that started in the top row, plus dx/2 (the
//                       surface lies half a spacing above them), over H, minus 1.
// The scene a free-surface scheme must keep for long (-t_end 50 for the verification table): a
// scheme that leaks through its floor, lets the lattice rearrange or diffuses the stratification
// fails it (docs/verification/free_surface.md).
#include <vector>

#include "src/run/case.hpp"

namespace sph {

template <int D> class StillWater : public Case<D> {
 public:
  std::string name() const override { return "still_water"; }
  void set_from_options() override;
  void create(Particles<D>& P, Domain<D>& domain) const override;
  double spacing() const override { return 1.0 / nx_; }
  double minimum_particles() const override {  // the water
    return D == 3 ? width_ * width_ * depth_ * nx_ * nx_ * nx_ : width_ * depth_ * nx_ * nx_;
  }
  int resolution() const override { return nx_; }
  Physics<D> physics() const override;
  double default_t_end() const override { return 50.0; }
  double wall_thickness() const override { return wall_layers_ * spacing(); }
  std::map<std::string, double> errors(const Particles<D>& P, double t) const override;
  nlohmann::json parameters() const override;

 private:
  // Every particle of the scene in the order create() lays them out: a particle's label is its index.
  Particles<D> lattice() const;

  PetscInt nx_ = 40, wall_layers_ = 4;
  PetscReal width_ = 1.0, depth_ = 0.5, g_ = 1.0, re_ = 500.0, rho0_ = 1.0;
  mutable std::vector<Vector<D>> start_;  // start position by label
  mutable std::vector<char> top_;         // 1: started in the top row of the fluid
};

}  // namespace sph
