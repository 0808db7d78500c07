// The WCSPH solver's options (-help's "Weakly-compressible SPH" block), their checks, and its
// description in summary.json. The step: wcsph_solver.cpp.
#include <cmath>
#include <sstream>

#include "solvers/wcsph/wcsph_solver.hpp"
#include "src/boundary/wall_options.hpp"
#include "src/core/option_reads.hpp"
#include "src/core/options.hpp"
#include "src/sph/operator_options.hpp"
#include "src/sph/step_limits.hpp"

namespace sph {

namespace {
const char* const density_names[] = {"continuity", "summation"};
const char* const diffusion_names[] = {"none", "molteni", "antuono", "particle", "fourtakas"};
const char* const diffusion_models[] = {"none", "MolteniColagrossi", "Antuono", "MolteniColagrossiParticleScale",
                                        "Fourtakas"};
const char* const gradient_names[] = {"auto", "corrected", "symmetric"};
const char* const outlet_names[] = {"fixed", "transmissive"};

struct RawOptions {
  PetscReal c0, c0_factor, gamma, cfl, delta, alpha, beta, epsilon, outlet_relaxation;
  PetscInt density, diffusion, operators, viscous_laplacian, gradient, outlet;
  PetscBool closed_volume, closed_volume_set;
  PetscBool diffusion_set;
  PetscBool prepared_start;
  PetscBool diffusion_at_surface;
  WallOptions walls;
};

PetscErrorCode read_options(RawOptions* o) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(PETSC_COMM_WORLD, nullptr, "Weakly-compressible SPH (-solver wcsph)", "Solver");
  PetscCall(option_real(PetscOptionsObject, "-c0",
                        "Reference sound speed (0: c0_factor times the largest of the flow's speed scales)", o->c0,
                        &o->c0, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-c0_factor",
                        "c0 / V when -c0 is not given, V the largest of U_ref, sqrt(|g| H) and sqrt(nu U_ref / L) "
                        "(Morris et al. 1997; 10 keeps density variations ~1%)",
                        o->c0_factor, &o->c0_factor, nullptr));
  PetscCall(
      option_real(PetscOptionsObject, "-tait_gamma", "Tait equation-of-state exponent", o->gamma, &o->gamma, nullptr));
  PetscCall(
      option_real(PetscOptionsObject, kAcousticCfl,
                  "WCSPH: acoustic Courant number, dt <= acoustic_cfl h / (c0 + U_max) (ISPH's advective one is -cfl)",
                  o->cfl, &o->cfl, nullptr));
  PetscCall(option_choice(PetscOptionsObject, "-density", "Density: continuity equation or kernel summation",
                          density_names, 2, density_names[o->density], &o->density, nullptr));
  PetscCall(option_choice(PetscOptionsObject, "-density_diffusion",
                          "delta-SPH density diffusion: none, molteni (2009), antuono (2010), particle (molteni "
                          "on the density's particle-scale part, rho minus its kernel average; scenes without "
                          "walls or a free surface), fourtakas (molteni without the hydrostatic density "
                          "difference, Fourtakas et al. 2019; the default under gravity, else molteni)",
                          diffusion_names, 5, diffusion_names[o->diffusion], &o->diffusion, &o->diffusion_set));
  PetscCall(option_real(PetscOptionsObject, "-delta", "delta-SPH coefficient", o->delta, &o->delta, nullptr));
  PetscCall(option_bool(PetscOptionsObject, "-density_diffusion_at_surface",
                        "Let the density diffusion drain the free surface's layer into the fluid inside "
                        "(default off: across the cut support it drains the layer's hydrostatic density, and "
                        "still water sinks; diffusion into the layer, as under tension, stays on)",
                        o->diffusion_at_surface, &o->diffusion_at_surface, nullptr, OptionLevel::expert));
  PetscCall(
      option_real(PetscOptionsObject, "-av_alpha",
                  "WCSPH: Monaghan artificial viscosity alpha (default 0: off; the compressible solver's default is 1)",
                  o->alpha, &o->alpha, nullptr));
  PetscCall(
      option_real(PetscOptionsObject, "-av_beta", "Monaghan artificial viscosity beta", o->beta, &o->beta, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-av_epsilon", "Artificial viscosity singularity guard epsilon", o->epsilon,
                        &o->epsilon, nullptr, OptionLevel::expert));
  PetscCall(option_choice(PetscOptionsObject, scheme_option(kWcsphPrefix, "operators").c_str(),
                          "Continuity divergence and viscous Laplacian: consistent (corrected divergence, "
                          "consistent Laplacian) or classic (plain divergence, Morris)",
                          operator_set_names, 2, operator_set_names[o->operators], &o->operators, nullptr));
  PetscCall(read_shared_operator_options(PetscOptionsObject, &o->viscous_laplacian));
  PetscCall(option_choice(PetscOptionsObject, scheme_option(kWcsphPrefix, "pressure_gradient").c_str(),
                          "Pressure force: corrected (Bonet & Lok, p_j - p_i), symmetric (Monaghan, momentum-"
                          "conserving), auto (symmetric with a free surface, whose zero pressure it imposes; "
                          "else corrected)",
                          gradient_names, 3, gradient_names[o->gradient], &o->gradient, nullptr));
  PetscCall(option_choice(PetscOptionsObject, "-outlet_pressure",
                          "Outlets' pressure: transmissive (the fluid's, carried outwards, its level relaxed to "
                          "the outlet's: sound leaves the box) or fixed (the outlet's on every buffer particle: "
                          "sound reflects back into the box)",
                          outlet_names, 2, outlet_names[o->outlet], &o->outlet, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-outlet_relaxation",
                        "Transmissive outlets: sigma, the level's relaxation rate sigma c0 / L (L the box's length "
                        "along the outlet's axis; Poinsot & Lele 1992)",
                        o->outlet_relaxation, &o->outlet_relaxation, nullptr, OptionLevel::expert));
  PetscCall(option_bool(PetscOptionsObject, "-closed_volume",
                        "Keep the fluid volume of a scene without a free surface: the net volume rate of the "
                        "continuity equation, which a closed or periodic box does not allow, is removed "
                        "(default: on without a free surface)",
                        o->closed_volume, &o->closed_volume, &o->closed_volume_set));
  PetscCall(option_bool(PetscOptionsObject, "-prepared_start",
                        "Start on the weakly compressible flow's slow manifold: add the compressive velocity "
                        "grad phi, lap phi = -(Dp/Dt) / (rho0 c0^2), that the case's incompressible start "
                        "implies, so that it excites no sound of O(Mach) pressure (cases with an exact "
                        "solution: taylor_green)",
                        o->prepared_start, &o->prepared_start, nullptr));
  PetscCall(read_wall_options(PetscOptionsObject, &o->walls));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}
}  // namespace

template <int D> void WcsphSolver<D>::set_from_options() {
  RawOptions o{
      c0_,
      c0_factor_,
      eos_.gamma,
      cfl_,
      delta_,
      av_.alpha,
      av_.beta,
      av_.epsilon,
      outlet_relaxation_,
      static_cast<PetscInt>(density_),
      static_cast<PetscInt>(diffusion_),
      static_cast<PetscInt>(operators_),
      static_cast<PetscInt>(viscous_laplacian_),
      static_cast<PetscInt>(gradient_),
      static_cast<PetscInt>(outlet_pressure_),
      closed_volume_option_ > 0 ? PETSC_TRUE : PETSC_FALSE,
      PETSC_FALSE,
      PETSC_FALSE,
      prepared_start_ ? PETSC_TRUE : PETSC_FALSE,
      diffusion_at_surface_ ? PETSC_TRUE : PETSC_FALSE,
      {wall_bounding_option_ > 0 ? PETSC_TRUE : PETSC_FALSE, PETSC_FALSE, static_cast<PetscInt>(wall_pressure_)}};
  SPH_PETSC(read_options(&o));
  require(o.c0 >= 0, "-c0", "non-negative", o.c0);
  require(o.c0_factor > 0, "-c0_factor", "positive", o.c0_factor);
  require(o.gamma >= 1, "-tait_gamma", "at least 1", o.gamma);
  require(o.cfl > 0 && o.cfl <= 1, kAcousticCfl, "in (0, 1]", o.cfl);
  require(o.delta >= 0, "-delta", "non-negative", o.delta);
  require(o.alpha >= 0, "-av_alpha", "non-negative", o.alpha);
  require(o.beta >= 0, "-av_beta", "non-negative", o.beta);
  require(o.epsilon > 0, "-av_epsilon", "positive", o.epsilon);
  require(o.outlet_relaxation >= 0, "-outlet_relaxation", "non-negative", o.outlet_relaxation);
  if (o.closed_volume_set) closed_volume_option_ = o.closed_volume ? 1 : 0;
  prepared_start_ = o.prepared_start;
  diffusion_at_surface_ = o.diffusion_at_surface;
  if (o.walls.bounding_set) wall_bounding_option_ = o.walls.bounding ? 1 : 0;
  c0_ = o.c0, c0_factor_ = o.c0_factor, eos_.gamma = o.gamma, cfl_ = o.cfl, delta_ = o.delta;
  av_.alpha = o.alpha, av_.beta = o.beta, av_.epsilon = o.epsilon;
  density_ = static_cast<DensityMethod>(o.density);
  operators_ = static_cast<OperatorSet>(o.operators);
  viscous_laplacian_ = static_cast<ViscousLaplacian>(o.viscous_laplacian);
  gradient_ = static_cast<WcsphGradient>(o.gradient);
  outlet_pressure_ = static_cast<OutletPressure>(o.outlet), outlet_relaxation_ = o.outlet_relaxation;
  wall_pressure_ = static_cast<WallPressure>(o.walls.pressure);
  diffusion_ = static_cast<DensityDiffusion>(o.diffusion);
  diffusion_chosen_ = o.diffusion_set;
  if (delta_ == 0.0) diffusion_ = DensityDiffusion::None;
  shifting_model_.set_from_options();
  free_surface_.set_from_options();
}

template <int D> nlohmann::json WcsphSolver<D>::describe() const {
  const Physics<D>& phys = disc_->physics;
  nlohmann::json models = nlohmann::json::object();
  models["equation_of_state"] = {{"model", "Tait"}, {"c0", eos_.c0}, {"gamma", eos_.gamma}, {"rho0", eos_.rho0}};
  if (c0_ == 0) models["equation_of_state"]["c0_set_by"] = speed_scale_name_;
  models["density"] = density_names[static_cast<int>(density_)];
  if (diffusion_ != DensityDiffusion::None && density_ == DensityMethod::Continuity)
    models["density_diffusion"] = {{"model", diffusion_models[static_cast<int>(diffusion_)]},
                                   {"delta", delta_},
                                   {"out_of_free_surface_layer", !phys.free_surface || diffusion_at_surface_}};
  if (av_.active())
    models["artificial_viscosity"] = {
        {"model", "MonaghanAV"}, {"alpha", av_.alpha}, {"beta", av_.beta}, {"epsilon", av_.epsilon}};
  if (phys.viscous())
    models["viscosity"] = {
        {"model", operators_ == OperatorSet::Consistent ? "ConsistentLaplacian" : "MorrisViscosity"},
        {"nu", phys.nu},
        {"smoothing_error",
         smoothing_error_description(operators_ == OperatorSet::Consistent &&
                                     viscous_laplacian_ == ViscousLaplacian::Fourth && !phys.free_surface)}};
  if (phys.has_body_force()) models["body_force"] = phys.describe()["gravity"];
  if (walls_)
    models["walls"] = {{"model", "AdamiWall"}, {"pressure", wall_pressure_names[static_cast<int>(wall_pressure_)]}};
  if (disc_->open.has_outlet()) {
    models["outlets"] = {{"pressure", outlet_names[static_cast<int>(outlet_pressure_)]}};
    if (outlet_pressure_ == OutletPressure::Transmissive) models["outlets"]["relaxation_sigma"] = outlet_relaxation_;
  }
  if (walls_ && bound_to_walls_) models["walls"]["bounding"] = {{"moves", bounded_}};  // particle-steps
  models["operators"] = operator_set_names[static_cast<int>(operators_)];
  models["pressure_gradient"] = gradient_names[static_cast<int>(gradient_)];
  if (shifting_model_.enabled) models["shifting"] = shifting_model_.describe();
  if (phys.free_surface) models["free_surface"] = free_surface_.describe();
  if (closed_volume_ && density_ == DensityMethod::Continuity) models["closed_volume"] = true;
  if (prepared_start_) models["start"] = "slow manifold (case's compressive velocity added)";
  // Mean fluid density over rho0, minus 1: the volume drift of a closed scene (the cavity).
  const Particles<D>& P = disc_->particles;
  double sums[2] = {0.0, 0.0};
  for (std::size_t i = 0; i < P.n_owned; ++i)
    if (P.kind[i] == kFluid) sums[0] += P.rho[i], sums[1] += 1.0;
  MPI_Allreduce(MPI_IN_PLACE, sums, 2, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  const double mean_rho = sums[1] > 0 ? sums[0] / sums[1] : eos_.rho0;
  return {{"models", models},
          {"cfl", cfl_},
          {"mean_fluid_density", mean_rho},
          {"conservation", {{"mean_fluid_density_rel", mean_rho / eos_.rho0 - 1.0}}}};
}

// The solver's other members are instantiated with the class in its own file.
template void WcsphSolver<1>::set_from_options();
template nlohmann::json WcsphSolver<1>::describe() const;
template void WcsphSolver<2>::set_from_options();
template nlohmann::json WcsphSolver<2>::describe() const;
template void WcsphSolver<3>::set_from_options();
template nlohmann::json WcsphSolver<3>::describe() const;

}  // namespace sph
