#pragma once
// Incompressible SPH by divergence-free projection (Cummins & Rudman 1999; Lind et al. 2012):
//   u*      = u^n + dt (nu lap u^n + g)                      Morris et al. (1997) viscous term
//   x*      = x^n + dt u^n                                   (the projection is made at x*)
//   div(grad p / rho) = div(u*) / dt                         PressurePoisson (PETSc + hypre)
//   u^{n+1} = u* - dt grad p / rho
//   x^{n+1} = x^n + dt (u^n + u^{n+1}) / 2
//   shifting (LindShifting) with a Taylor correction of u to the shifted positions.
// Density stays at rho0 (the divergence-free variant); the time step obeys the advective CFL and the
// viscous limit only: no sound speed, which is ISPH's advantage over WCSPH.
#include "solvers/isph/pressure_poisson.hpp"
#include "solvers/solver.hpp"
#include "src/sph/shifting.hpp"

namespace sph {

enum class PressureGradient { Corrected, Difference, Symmetric };

template <int D> class IsphSolver : public Solver<D> {
 public:
  std::string name() const override { return "isph"; }
  void set_from_options() override;
  void setup(Scene<D>& scene) override;
  double stable_dt() const override;
  StepReport step(double dt) override;
  nlohmann::json describe() const override;
  nlohmann::json checkpoint_scalars() const override { return {{"pressure_solves", solves_}}; }
  void restore_scalars(const nlohmann::json& j) override { solves_ = j.value("pressure_solves", 0L); }

  const PressurePoisson<D>& pressure_poisson() const { return ppe_; }

 private:
  std::vector<Vector<D>> pressure_gradient() const;
  void shift();
  double max_speed() const;

  Scene<D>* scene_ = nullptr;
  PressurePoisson<D> ppe_;
  double cfl_ = 0.2;
  double viscous_dt_factor_ = 0.125;
  PetscBool shifting_ = PETSC_TRUE;
  LindShifting shifting_model_;
  PressureGradient gradient_ = PressureGradient::Corrected;
  long solves_ = 0;
  bool walls_ = false;
  PetscReal free_surface_threshold_ = 0.0;  // 0: the dimension's default
};

}  // namespace sph
