#pragma once
// Incompressible SPH by divergence-free projection (Cummins & Rudman 1999; Lind et al. 2012), in
// kick-drift-kick form (velocity Verlet, second order in dt) whose closing kick is the projection:
//   a^n       = -grad p^n / rho + nu lap u^n + g            at x^n (p^n: the last projection's)
//   u^{n+1/2} = u^n + dt/2 a^n,   x^{n+1} = x^n + dt u^{n+1/2}
//   u*        = u^{n+1/2} + dt/2 (nu lap u~ + g)            at x^{n+1}, u~ = u^{n+1/2} + dt/2 a^n
//   div(grad p^{n+1} / rho) = div(u*) / (dt/2)              PressurePoisson (PETSc + hypre)
//   u^{n+1}   = u* - dt/2 psi / rho                         divergence-free at x^{n+1}
//   correction pass: div(grad dpsi / rho) = <div u^{n+1}> / (dt/2),  u^{n+1} -= dt/2 grad dpsi / rho,
//                    psi += dpsi    (<.>: kernel average; the same matrix; -projection_corrections)
//   p^{n+1}   = pm^{n+1/2} + (pm^{n+1/2} - pm^{n-1/2}) / 2,  pm^{n+1/2} = (p^n + psi) / 2
//   shifting (LindShifting) with Taylor corrections of u, p and pm to the shifted positions.
// The projection fixes only the step's mean pressure pm (the impulse dt pm that makes u^{n+1}
// divergence-free); taking psi itself as p^{n+1} = 2 pm - p^n would carry any error of p^n into the
// next step with its sign flipped, a mode that never decays (docs/verification/taylor_green.md, "Design
// measurements"). The mean pressures have no memory of p^n, and extrapolating them to t^{n+1} is second
// order. The first step has no p^n: it projects with dt instead of dt/2 and takes p^1 = pm^{1/2} = psi.
//
// Why this form: a projection at x* = x^n + dt u^n with the whole pressure impulse there (pressure at the
// end of the step, viscosity at its start) is first order in dt, and with consistent operators that time
// error dominates (docs/verification/taylor_green.md, "History").
//
// Operators (-isph_operators): by default the consistent Laplacian (src/sph/consistent_laplacian.hpp) for
// the viscous term and the PPE, the corrected divergence for the PPE source and the corrected
// gradient for the pressure force: all exact for linear (the Laplacian: quadratic) fields on any
// particle distribution, so the projection leaves no first-order divergence of its own making that
// the next step must remove again (a second-order one it does: below). `-isph_operators classic` keeps the
// Morris viscous term, the Cummins & Rudman PPE and the plain divergence: a symmetric PPE (CG), kept for
// comparison only, being far less accurate (docs/verification/taylor_green.md, "Design measurements").
//
// The projection is approximate: the consistent Laplacian L is not the corrected divergence of the
// corrected gradient D G. On the resolved scales they differ at second order in h, and one projection
// leaves the divergence tau (L - D G) psi in u^{n+1}, which the next step removes again: an error of
// order dt h^2 in u, first order in dt. -projection_corrections K solves the same matrix K more times
// with the kernel average of the remaining divergence (its resolved part) and corrects again: each pass
// shrinks that divergence by the relative size of L - D G, so the time error is second order again
// (project(); docs/verification/taylor_green.md, "ISPH's time error" and "Design measurements").
// The source div u* / tau also divides by tau the particle-scale divergence that u^n keeps at the new
// positions and that no projection removes, a pressure noise growing as 1/dt;
// -ppe_particle_divergence_rate removes it at a rate per unit time instead (default 10 U/h: all of it
// at CFL 0.2, the same rate at smaller steps; isph_solver.cpp, project).
//
// Free surface (src/sph/free_surface.hpp, src/sph/surface_nodes.hpp): p = 0 holds at each surface
// particle's node, dx/2 beyond it, and the surface particle keeps its continuity equation, so that a
// jet that hits a wall or a pool is stopped by its own pressure; particles the solve would put under
// tension are let go (p = 0 on them), and sheets and drops too thin for a node take p = 0 themselves.
// Walls met head on add the pressure that stops the fluid within the step (-ppe_wall_impact). Why
// each of these: docs/verification/free_surface.md.
//
// Density stays at rho0 (the divergence-free variant); the time step obeys the advective CFL and the
// viscous limit only: no sound speed, which is ISPH's advantage over WCSPH.
#include "solvers/isph/pressure_poisson.hpp"
#include "src/boundary/wall_bounding.hpp"
#include "src/run/solver.hpp"
#include "src/sph/consistent_laplacian.hpp"
#include "src/sph/energy_budget.hpp"
#include "src/sph/free_surface.hpp"
#include "src/sph/kernel_average.hpp"
#include "src/sph/laplacian_smoothing.hpp"
#include "src/sph/operator_options.hpp"
#include "src/sph/shifting.hpp"
#include "src/sph/step_limits.hpp"

namespace sph {

enum class PressureGradient { Corrected, Difference, Symmetric };
// Where the free surface's p = 0 holds (-free_surface_condition): at each surface particle's node,
// dx/2 beyond it (src/sph/surface_nodes.hpp), or on the surface particles themselves.
enum class SurfaceCondition { Node, Particle };

template <int D> class IsphSolver : public Solver<D> {
 public:
  std::string name() const override { return "isph"; }
  std::string courant_option() const override { return kAdvectiveCfl; }
  // Measured: the PPE matrix, BoomerAMG's hierarchy and the step's arrays (docs/performance.md,
  // "Memory per particle").
  double bytes_per_particle() const override { return D == 3 ? 3.1e3 : 1.3e3; }
  double density_at_pressure(double) const override { return disc_->physics.rho0; }
  // The pressure solve, not the list rebuild, sets ISPH's step's cost: a thinner skin saves memory for
  // no time (docs/performance.md, "Memory per particle").
  double neighbour_skin() const override { return 0.1; }
  // The projection's pressure answers a body's acceleration in the same step: an explicit coupling
  // oscillates at the step's period unless it anticipates the added mass (free_body.hpp).
  double free_body_added_mass() const override { return 1.0; }
  void set_from_options() override;
  void setup(Discretisation<D>& disc) override;
  double stable_dt() const override;
  StepReport step(double dt) override;
  nlohmann::json describe() const override;
  bool reads_late(const std::string& option) const override { return PressurePoisson<D>::reads_late(option); }
  std::string options_prefix() const override { return kIsphPrefix; }
  RenamedOption renamed_option(const std::string& option) const override {
    const RenamedOption own = scheme_operator_rename(kIsphPrefix, option);
    return own.now.empty() ? PressurePoisson<D>::renamed_option(option) : own;
  }
  nlohmann::json checkpoint_scalars() const override {
    return {{"pressure_solves", solves_}, {"energy_budget", energy_.to_json()}};
  }
  void restore_scalars(const nlohmann::json& j) override {
    solves_ = j.value("pressure_solves", 0L);
    energy_.from_json(j.value("energy_budget", nlohmann::json()));
  }
  const EnergyBudget* energy_budget() const override { return &energy_; }
  EnergyBudget* energy_budget() override { return &energy_; }

 private:
  // What one step's phases hand on to the next (step()).
  struct StepState {
    bool have_pressure = false;  // a projection has run before: the opening kick has a pressure
    std::vector<Vector<D>> acc;  // a^n, the opening kick's acceleration (gravity included)
    std::vector<Vector<D>> u_half, u_star;
    std::vector<Vector<D>> u_start, viscous_kick;     // u^n and the viscous term's change of it, for the energy budget
    std::vector<LaplacianCorrection<D>> corrections;  // the consistent Laplacian's factors at x^{n+1}
  };
  void opening_kick_and_drift(double dt, StepState& s);
  void closing_kick_without_pressure(double dt, StepState& s);
  StepReport project_and_update_pressure(double dt, StepState& s);
  std::vector<Vector<D>> pressure_gradient(const std::vector<double>& p) const;  // p has ghost values
  // The PPE's divergence of u (with ghost values): the corrected one, or the plain one with classic
  // operators and, under the consistent ones, at the particles flagged in near_surface.
  // Under -ppe_wall_velocity zero, the fixed walls' velocity in the first field is tau g (in the
  // others zero), and a moving body's its own velocity, in the first field plus tau (g - a_w): what
  // its pressure rows hold (project). tau = 0: every wall at its own velocity, fixed ones at rest.
  std::vector<std::vector<double>> ppe_divergences(const std::vector<const std::vector<Vector<D>>*>& fields,
                                                   const std::vector<char>& near_surface, double tau) const;
  // nu lap u at the current positions (walls: Adami's mirrored velocity); u has ghost values. The
  // consistent Laplacian's factors are gathered in the same pass, and handed to `factors` if given.
  std::vector<Vector<D>> viscous_acceleration(const std::vector<Vector<D>>& u,
                                              std::vector<LaplacianCorrection<D>>* factors = nullptr) const;
  std::vector<LaplacianCorrection<D>> laplacian_corrections_if_used() const;
  // Makes P.v = u_star - tau grad p / rho divergence-free at the current positions; returns the solve.
  // The factors are taken: freed once the system is assembled.
  StepReport project(const std::vector<Vector<D>>& u_star, double tau, std::vector<LaplacianCorrection<D>> corrections);
  // What the projection's phases share: its pressure system's free surface and boundary rows.
  struct Projection {
    double tau = 0.0;
    bool consistent = false, nodes = false, outlets = false;
    std::vector<char> surface, near_surface, dirichlet;
    const std::vector<char>* surface_flags = nullptr;  // &surface with a free surface
    std::vector<Vector<D>> predicted, wall_normals, wall_acceleration;
    std::vector<double> impacting;
    std::vector<LaplacianCorrection<D>> corrections;
  };
  void detect_free_surface(Projection& j);
  std::vector<double> ppe_source(const std::vector<Vector<D>>& u_star, const Projection& j) const;
  void relax_number_density(std::vector<double>& source, const Projection& j) const;
  void prepare_wall_impact(const std::vector<Vector<D>>& u_star, Projection& j);
  void set_dirichlet_rows(Projection& j);
  void assemble(Projection& j);
  StepReport solve_releasing_tension(const std::vector<double>& source, Projection& j);
  void correction_pass(const Projection& j, PetscInt pass, StepReport& report);
  void shift(double dt);
  void bound_to_walls();
  void credit_velocity_update(double dt, const StepState& s);
  double max_speed() const;

  Discretisation<D>* disc_ = nullptr;
  PressurePoisson<D> ppe_;
  double cfl_ = 0.2;
  LindShifting shifting_model_;
  PressureGradient gradient_ = PressureGradient::Corrected;
  OperatorSet operators_ = OperatorSet::Consistent;
  ViscousLaplacian viscous_laplacian_ = ViscousLaplacian::Fourth;
  PetscReal particle_divergence_rate_ = 10;   // in U/h; -1: all of it every step; 10: all of it at CFL 0.2
  PetscReal density_relaxation_option_ = -1;  // -ppe_density_relaxation: -1 unset (1 with open boundaries, else 0)
  double density_relaxation_ = 0;             // in U/h (0: off)
  PetscInt projection_corrections_ = 1;       // correction passes after the projection
  bool source_walls_at_rest_ = true;          // -ppe_wall_velocity zero: the PPE source sees the walls at rest
  long solves_ = 0;
  FieldId<double> mean_pressure_;                     // pm^{n-1/2}, a particle field
  bool walls_ = false;                                // any wall particles
  WallPressure wall_pressure_ = WallPressure::Adami;  // -wall_pressure: the wall model
  FreeSurface<D> free_surface_model_;
  SurfaceCondition surface_condition_ = SurfaceCondition::Node;
  SurfaceNodes<D> nodes_;        // the free-surface nodes at the current positions (empty: none)
  int wall_impact_option_ = -1;  // -ppe_wall_impact: -1 unset (off), 0 off, 1 on
  bool wall_impact_ = false;
  int wall_bounding_option_ = -1;  // -wall_bounding: -1 unset (on with a free surface), 0 off, 1 on
  bool bound_to_walls_ = false;
  WallBounding<D> wall_bounding_;
  long bounded_ = 0;     // fluid particles put back on a wall's face, summed over the steps
  EnergyBudget energy_;  // since the run's start (kept in checkpoints)
};

}  // namespace sph
