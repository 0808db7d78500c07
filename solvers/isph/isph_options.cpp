// The ISPH solver's options (-help's "ISPH projection solver" block), their checks, and its
// description in summary.json. The step: isph_solver.cpp.
#include "solvers/isph/isph_solver.hpp"
#include "src/boundary/wall_options.hpp"
#include "src/core/option_reads.hpp"
#include "src/core/options.hpp"
#include "src/sph/operator_options.hpp"
#include "src/sph/step_limits.hpp"

namespace sph {

namespace {
const char* const gradient_names[] = {"corrected", "difference", "symmetric"};
const char* const wall_velocity_names[] = {"prescribed", "zero"};
const char* const surface_condition_names[] = {"node", "particle"};

struct RawOptions {
  PetscReal cfl, particle_divergence_rate, density_relaxation;
  PetscInt gradient, operators, viscous_laplacian, projection_corrections, wall_velocity, surface_condition;
  PetscBool wall_impact, wall_impact_set;
  WallOptions walls;
};

PetscErrorCode read_options(RawOptions* o) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(PETSC_COMM_WORLD, nullptr, "ISPH projection solver (-solver isph)", "Solver");
  PetscCall(option_real(PetscOptionsObject, kAdvectiveCfl,
                        "ISPH: advective Courant number, dt <= cfl h / U (the explicit schemes' is -acoustic_cfl)",
                        o->cfl, &o->cfl, nullptr));
  PetscCall(option_choice(PetscOptionsObject, scheme_option(kIsphPrefix, "pressure_gradient").c_str(),
                          "Pressure gradient: corrected (Bonet & Lok), difference, symmetric (Monaghan)",
                          gradient_names, 3, gradient_names[o->gradient], &o->gradient, nullptr));
  PetscCall(option_choice(PetscOptionsObject, scheme_option(kIsphPrefix, "operators").c_str(),
                          "Viscous and PPE Laplacian, PPE divergence: consistent (exact for quadratic / linear "
                          "fields on any particle distribution) or classic (Morris, Cummins & Rudman, plain)",
                          operator_set_names, 2, operator_set_names[o->operators], &o->operators, nullptr));
  PetscCall(read_shared_operator_options(PetscOptionsObject, &o->viscous_laplacian));
  PetscCall(option_real(PetscOptionsObject, "-ppe_particle_divergence_rate",
                        "Rate, in U/h, at which the PPE removes the particle-scale divergence of the previous "
                        "step's velocity, which the projection cannot remove (R: a fraction R U dt / (2 h) per "
                        "step, at most all, so the default 10 removes all of it at CFL 0.2 and keeps that rate "
                        "at smaller steps; -1: all of it every step, whatever dt; 0: never)",
                        o->particle_divergence_rate, &o->particle_divergence_rate, nullptr, OptionLevel::expert));
  PetscCall(option_real(PetscOptionsObject, "-ppe_density_relaxation",
                        "Rate, in U/h, at which the PPE returns the fluid's number density (its kernel sum, where "
                        "the support holds no free surface) to the lattice's: the projection keeps the velocity "
                        "divergence-free, not the particles' volume, whose error grows along a through-flow's "
                        "path (docs/verification/open_boundaries.md, the bump channel); 0: off; default 1 in "
                        "scenes with inlets or outlets, else 0",
                        o->density_relaxation, &o->density_relaxation, nullptr, OptionLevel::expert));
  PetscCall(option_int(PetscOptionsObject, "-projection_corrections",
                       "Passes after the projection that remove the resolved-scale divergence it leaves (its "
                       "Laplacian is not the divergence of its gradient): each solves the same matrix again; 0: "
                       "one projection, first order in dt",
                       o->projection_corrections, &o->projection_corrections, nullptr, OptionLevel::expert));
  PetscCall(option_choice(PetscOptionsObject, "-ppe_wall_velocity",
                          "Wall velocity the PPE source's divergence sees: zero (walls at rest, as in WCSPH's "
                          "continuity equation; wall particles keep their place, so every wall here is fixed or "
                          "slides along itself) or prescribed (the walls' own: a sliding wall's velocity jump "
                          "where it ends reads as a compression, a first-order error)",
                          wall_velocity_names, 2, wall_velocity_names[o->wall_velocity], &o->wall_velocity, nullptr,
                          OptionLevel::expert));
  PetscCall(option_bool(PetscOptionsObject, "-ppe_wall_impact",
                        "Walls stop the free surface that comes at them within the step: their pressure rows add "
                        "rho u_n (r . n) / tau for a surface particle's predicted velocity u_n towards them "
                        "(default off: once per step, it fed the flow energy as the step fell; -wall_bounding "
                        "stops such fluid instead)",
                        o->wall_impact, &o->wall_impact, &o->wall_impact_set, OptionLevel::expert));
  PetscCall(read_wall_options(PetscOptionsObject, &o->walls));
  PetscCall(option_choice(PetscOptionsObject, "-free_surface_condition",
                          "Where p = 0 holds: node (at the surface, dx/2 beyond each surface particle, which "
                          "keeps its continuity equation) or particle (on the surface particles, Lind et al. 2012)",
                          surface_condition_names, 2, surface_condition_names[o->surface_condition],
                          &o->surface_condition, nullptr, OptionLevel::expert));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}
}  // namespace

template <int D> void IsphSolver<D>::set_from_options() {
  RawOptions o{
      cfl_,
      particle_divergence_rate_,
      density_relaxation_option_,
      static_cast<PetscInt>(gradient_),
      static_cast<PetscInt>(operators_),
      static_cast<PetscInt>(viscous_laplacian_),
      projection_corrections_,
      source_walls_at_rest_ ? 1 : 0,
      static_cast<PetscInt>(surface_condition_),
      PETSC_FALSE,
      PETSC_FALSE,
      {wall_bounding_option_ > 0 ? PETSC_TRUE : PETSC_FALSE, PETSC_FALSE, static_cast<PetscInt>(wall_pressure_)}};
  SPH_PETSC(read_options(&o));
  require(o.cfl > 0 && o.cfl <= 1.0, kAdvectiveCfl, "in (0, 1]", o.cfl);
  require(o.particle_divergence_rate >= 0 || o.particle_divergence_rate == -1, "-ppe_particle_divergence_rate",
          "non-negative (or -1: all of it every step)", o.particle_divergence_rate);
  require(o.projection_corrections >= 0, "-projection_corrections", "non-negative", o.projection_corrections);
  require(o.density_relaxation >= 0 || o.density_relaxation == -1, "-ppe_density_relaxation", "non-negative",
          o.density_relaxation);
  cfl_ = o.cfl, particle_divergence_rate_ = o.particle_divergence_rate;
  density_relaxation_option_ = o.density_relaxation;
  gradient_ = static_cast<PressureGradient>(o.gradient), operators_ = static_cast<OperatorSet>(o.operators);
  viscous_laplacian_ = static_cast<ViscousLaplacian>(o.viscous_laplacian);
  projection_corrections_ = o.projection_corrections, source_walls_at_rest_ = o.wall_velocity == 1;
  surface_condition_ = static_cast<SurfaceCondition>(o.surface_condition);
  wall_pressure_ = static_cast<WallPressure>(o.walls.pressure);
  wall_impact_option_ = o.wall_impact_set ? (o.wall_impact ? 1 : 0) : -1;
  if (o.walls.bounding_set) wall_bounding_option_ = o.walls.bounding ? 1 : 0;
  shifting_model_.set_from_options();
  free_surface_model_.set_from_options();
  ppe_.expect_nonsymmetric(operators_ == OperatorSet::Consistent);
  ppe_.set_from_options();
}

template <int D> nlohmann::json IsphSolver<D>::describe() const {
  const Physics<D>& phys = disc_->physics;
  nlohmann::json models = nlohmann::json::object();
  const bool consistent = operators_ == OperatorSet::Consistent;
  models["pressure_laplacian"] = consistent ? "ConsistentLaplacian" : "CumminsRudman";
  models["ppe_source"] = {{"divergence", consistent ? "corrected" : "plain"},
                          {"particle_divergence_rate", particle_divergence_rate_},
                          {"density_relaxation", density_relaxation_},
                          {"wall_velocity", wall_velocity_names[source_walls_at_rest_ ? 1 : 0]}};
  models["projection_corrections"] = projection_corrections_;
  models["time_integration"] = "kick-drift-kick, projection as the closing kick";
  if (walls_)
    models["walls"] = {{"model", "AdamiWall"},
                       {"ppe", phys.free_surface ? "extrapolation rows" : "extrapolation rows, diagonal regularised"},
                       {"pressure", wall_pressure_names[static_cast<int>(wall_pressure_)]}};
  if (phys.free_surface) {
    models["free_surface"] = free_surface_model_.describe();
    models["free_surface"]["condition"] = surface_condition_names[static_cast<int>(surface_condition_)];
    models["free_surface"]["model"] = surface_condition_ == SurfaceCondition::Node ? "SurfaceNodes" : "LindFreeSurface";
  }
  if (bound_to_walls_) models["walls"]["bounding"] = {{"moves", bounded_}};  // particle-steps
  if (wall_impact_) models["walls"]["impact"] = "rho u_n (r . n) / tau for surface particles moving towards a wall";
  models["pressure_gradient"] = gradient_names[static_cast<int>(gradient_)];
  if (phys.viscous())
    models["viscosity"] = {
        {"model", consistent ? "ConsistentLaplacian" : "MorrisViscosity"},
        {"nu", phys.nu},
        {"smoothing_error", smoothing_error_description(consistent && viscous_laplacian_ == ViscousLaplacian::Fourth &&
                                                        !phys.free_surface)}};
  if (phys.has_body_force()) models["body_force"] = phys.describe()["gravity"];
  if (shifting_model_.enabled) models["shifting"] = shifting_model_.describe();
  return {{"models", models}, {"cfl", cfl_}, {"ksp", ppe_.describe()}};
}

// The solver's other members are instantiated with the class in its own file.
template void IsphSolver<1>::set_from_options();
template nlohmann::json IsphSolver<1>::describe() const;
template void IsphSolver<2>::set_from_options();
template nlohmann::json IsphSolver<2>::describe() const;
template void IsphSolver<3>::set_from_options();
template nlohmann::json IsphSolver<3>::describe() const;

}  // namespace sph
