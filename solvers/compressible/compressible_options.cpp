// The compressible solver's options (-help's "Compressible SPH" block), their checks, and its
// description in summary.json. The step: compressible_solver.cpp.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "solvers/compressible/compressible_solver.hpp"
#include "src/core/option_reads.hpp"
#include "src/core/options.hpp"
#include "src/sph/step_limits.hpp"

namespace sph {

namespace {
const char* const viscosity_names[] = {"none", "signal_velocity", "monaghan"};
const char* const switch_names[] = {"none", "morris_monaghan"};

struct RawOptions {
  PetscReal cfl, cfl_force, eta, h_tol, alpha, beta, epsilon, alpha_min, alpha_max, sigma, alpha_u;
  PetscInt viscosity, av_switch;
  PetscBool balsara, conductivity;
};

PetscErrorCode read_options(RawOptions* o) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(PETSC_COMM_WORLD, nullptr, "Compressible SPH, ideal gas with grad-h terms (-solver compressible)",
                    "Solver");
  PetscCall(option_real(PetscOptionsObject, kAcousticCfl,
                        "Compressible: Courant number on the signal velocity, dt <= acoustic_cfl h_i / v_sig,i", o->cfl,
                        &o->cfl, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-cfl_force", "Force criterion: dt <= cfl_force sqrt(h_i / |a_i|)",
                        o->cfl_force, &o->cfl_force, nullptr, OptionLevel::expert));
  PetscCall(option_real(PetscOptionsObject, "-eta",
                        "Smoothing length h_i = eta (m_i/rho_i)^(1/D) (0: the kernel's default)", o->eta, &o->eta,
                        nullptr, OptionLevel::expert));
  PetscCall(option_real(PetscOptionsObject, "-h_tolerance", "Relative tolerance of the Newton-Raphson iteration for h",
                        o->h_tol, &o->h_tol, nullptr, OptionLevel::expert));
  PetscCall(option_choice(PetscOptionsObject, "-av",
                          "Artificial viscosity: none, signal_velocity (Monaghan 1997), monaghan (1992)",
                          viscosity_names, 3, viscosity_names[o->viscosity], &o->viscosity, nullptr));
  PetscCall(option_real(
      PetscOptionsObject, "-av_alpha",
      "Compressible: artificial viscosity alpha (default 1, initial alpha with -av_switch; WCSPH's default is 0)",
      o->alpha, &o->alpha, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-av_beta",
                        "Artificial viscosity beta (-1: 3 for signal_velocity, 2 for monaghan)", o->beta, &o->beta,
                        nullptr));
  PetscCall(option_real(PetscOptionsObject, "-av_epsilon", "Singularity guard of the monaghan viscosity", o->epsilon,
                        &o->epsilon, nullptr, OptionLevel::expert));
  PetscCall(option_choice(PetscOptionsObject, "-av_switch", "Time-dependent alpha: none, morris_monaghan (1997)",
                          switch_names, 2, switch_names[o->av_switch], &o->av_switch, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-av_alpha_min", "Morris-Monaghan: alpha far from shocks", o->alpha_min,
                        &o->alpha_min, nullptr, OptionLevel::expert));
  PetscCall(option_real(PetscOptionsObject, "-av_alpha_max", "Morris-Monaghan: largest alpha", o->alpha_max,
                        &o->alpha_max, nullptr, OptionLevel::expert));
  PetscCall(option_real(PetscOptionsObject, "-av_decay", "Morris-Monaghan: decay rate sigma, tau = h / (sigma c)",
                        o->sigma, &o->sigma, nullptr, OptionLevel::expert));
  PetscCall(option_bool(PetscOptionsObject, "-balsara", "Balsara (1995) switch on the artificial viscosity", o->balsara,
                        &o->balsara, nullptr));
  PetscCall(option_bool(PetscOptionsObject, "-conductivity", "Artificial thermal conductivity (Price 2008)",
                        o->conductivity, &o->conductivity, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-conductivity_alpha", "Artificial conductivity coefficient alpha_u",
                        o->alpha_u, &o->alpha_u, nullptr, OptionLevel::expert));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

}  // namespace

template <int D> void CompressibleSolver<D>::set_from_options() {
  RawOptions o{cfl_,
               cfl_force_,
               eta_,
               h_tolerance_,
               av_.alpha,
               -1.0,
               av_.epsilon,
               alpha_min_,
               alpha_max_,
               mm_sigma_,
               alpha_u_,
               static_cast<PetscInt>(av_.model),
               static_cast<PetscInt>(switch_),
               balsara_,
               conductivity_};
  SPH_PETSC(read_options(&o));
  require(o.cfl > 0 && o.cfl <= 1, kAcousticCfl, "in (0, 1]", o.cfl);
  require(o.cfl_force > 0 && o.cfl_force <= 1, "-cfl_force", "in (0, 1]", o.cfl_force);
  require(o.eta >= 0, "-eta", "non-negative (0: kernel default)", o.eta);
  require(o.h_tol > 0 && o.h_tol < 0.1, "-h_tolerance", "in (0, 0.1)", o.h_tol);
  require(o.alpha >= 0, "-av_alpha", "non-negative", o.alpha);
  require(o.beta >= 0 || o.beta == -1, "-av_beta", "non-negative (or -1 for the model's default)", o.beta);
  require(o.epsilon > 0, "-av_epsilon", "positive", o.epsilon);
  require(o.alpha_min >= 0, "-av_alpha_min", "non-negative", o.alpha_min);
  require(o.alpha_max >= o.alpha_min, "-av_alpha_max", "at least -av_alpha_min", o.alpha_max);
  require(o.sigma > 0, "-av_decay", "positive", o.sigma);
  require(o.alpha_u >= 0, "-conductivity_alpha", "non-negative", o.alpha_u);
  cfl_ = o.cfl, cfl_force_ = o.cfl_force, eta_ = o.eta, h_tolerance_ = o.h_tol;
  av_.model = static_cast<compressible::ViscosityModel>(o.viscosity);
  av_.alpha = o.alpha, av_.epsilon = o.epsilon;
  av_.beta = o.beta >= 0 ? o.beta : (av_.model == compressible::ViscosityModel::Monaghan1992 ? 2.0 : 3.0);
  switch_ = static_cast<ViscositySwitch>(o.av_switch);
  alpha_min_ = o.alpha_min, alpha_max_ = o.alpha_max, mm_sigma_ = o.sigma;
  balsara_ = o.balsara, conductivity_ = o.conductivity, alpha_u_ = o.alpha_u;
  if (alpha_u_ == 0.0) conductivity_ = PETSC_FALSE;
  if (!av_.active()) switch_ = ViscositySwitch::None, balsara_ = PETSC_FALSE;
}

template <int D> nlohmann::json CompressibleSolver<D>::describe() const {
  const Physics<D>& phys = disc_->physics;
  nlohmann::json models = nlohmann::json::object();
  models["equation_of_state"] = {{"model", "IdealGas"}, {"gamma", gamma_}};
  models["energy_equation"] =
      entropy_ ? nlohmann::json{{"model", "Isentropic"}, {"variable", "A = P/rho^gamma (Springel & Hernquist 2002)"}}
               : nlohmann::json{{"model", "ThermalEnergy"}, {"variable", "u"}};
  models["smoothing_length"] = {{"model", "GradH"}, {"eta", eta_}, {"tolerance", h_tolerance_}};
  if (av_.model == compressible::ViscosityModel::SignalVelocity)
    models["artificial_viscosity"] = {{"model", "MonaghanSignalVelocity"}, {"alpha", av_.alpha}, {"beta", av_.beta}};
  else if (av_.model == compressible::ViscosityModel::Monaghan1992)
    models["artificial_viscosity"] = {
        {"model", "MonaghanAV"}, {"alpha", av_.alpha}, {"beta", av_.beta}, {"epsilon", av_.epsilon}};
  if (balsara_) models["balsara"] = {{"model", "Balsara1995"}};
  if (switch_ == ViscositySwitch::MorrisMonaghan)
    models["viscosity_switch"] = {
        {"model", "MorrisMonaghan1997"}, {"alpha_min", alpha_min_}, {"alpha_max", alpha_max_}, {"decay", mm_sigma_}};
  if (conductivity_) models["conductivity"] = {{"model", "Price2008"}, {"alpha_u", alpha_u_}};
  if (phys.has_body_force()) models["body_force"] = phys.describe()["gravity"];
  if (phys.has_external_force()) models["external_force"] = phys.describe()["external_acceleration"];
  models["time_integration"] = "KickDriftKickLeapfrog";

  // Conservation since setup: momentum relative to the larger of the initial and current sum of |m v|
  // (a gas starting at rest has no initial scale), energy = kinetic + thermal + external potential.
  const Particles<D>& P = disc_->particles;
  double scale = 0.0;
  for (std::size_t i = 0; i < P.n_owned; ++i) scale += P.m[i] * P.v[i].norm();
  MPI_Allreduce(MPI_IN_PLACE, &scale, 1, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  const double dP = (total_momentum() - momentum0_).norm();
  const double E = total_energy();
  nlohmann::json conservation = {{"momentum_drift", dP / std::max({scale, momentum_scale0_, 1e-300})},
                                 {"momentum_change", dP},
                                 {"energy_initial", energy0_},
                                 {"energy_drift_rel", std::abs(E - energy0_) / std::max(std::abs(energy0_), 1e-300)}};
  return {{"models", models},
          {"cfl", cfl_},
          {"cfl_force", cfl_force_},
          {"smoothing_length_range", {h_min_seen_, h_max_seen_}},
          {"density_iterations_max", density_iterations_max_},
          {"search_radius_changes", radius_changes_},
          {"neighbour_rebuilds", disc_->neighbourhood.rebuilds()},
          {"conservation", conservation}};
}

// The solver's other members are instantiated with the class in its own file.
template void CompressibleSolver<1>::set_from_options();
template nlohmann::json CompressibleSolver<1>::describe() const;
template void CompressibleSolver<2>::set_from_options();
template nlohmann::json CompressibleSolver<2>::describe() const;
template void CompressibleSolver<3>::set_from_options();
template nlohmann::json CompressibleSolver<3>::describe() const;

}  // namespace sph
