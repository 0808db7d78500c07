#pragma once
// Weakly-compressible SPH (Monaghan 1994, 2005): the explicit twin of ISPH on the same kernels,
// neighbour search and cases. Pressure from the Tait equation of state; density by continuity (default)
// or summation; optional delta-SPH density diffusion (Molteni & Colagrossi 2009; Antuono et al. 2010;
// or the former on the density's particle-scale part only),
// Monaghan (1992) artificial viscosity, Morris et al. (1997) laminar viscosity; kick-drift-kick
// leapfrog (Monaghan 2005, sec. 5.3); dt from the acoustic CFL, viscous and force limits.
#include "solvers/wcsph/wcsph_iact.hpp"
#include "src/boundary/wall_bounding.hpp"
#include "src/run/solver.hpp"
#include "src/sph/consistent_laplacian.hpp"
#include "src/sph/free_surface.hpp"
#include "src/sph/laplacian_smoothing.hpp"
#include "src/sph/operator_options.hpp"
#include "src/sph/shifting.hpp"
#include "src/sph/step_limits.hpp"

namespace sph {

enum class DensityMethod { Continuity, Summation };
// delta-SPH density diffusion (-density_diffusion). delta-SPH is there to damp particle-scale density
// noise, at the rate delta c0 pi^2 / h; on the resolved flow it is a diffusivity delta h c0, first
// order in h at fixed c0 and delta. particle: the Molteni-Colagrossi term acting on rho minus its
// kernel (Shepard) average, the part of rho that varies on the particle scale, so that the resolved
// density is diffused O(h^2) less and delta need not fall with h: with c0 ~ 1/h WCSPH then converges at
// second order where Molteni's term with delta ~ h^2 does not (docs/verification/taylor_green.md, "WCSPH
// with particle-scale delta-SPH"). Needs supports of fluid only: scenes with walls or a free surface are refused.
enum class DensityDiffusion { None, Molteni, Antuono, Particle, Fourtakas };
enum class WcsphGradient { Auto, Corrected, Symmetric };

template <int D> class WcsphSolver : public Solver<D> {
 public:
  std::string name() const override { return "wcsph"; }
  std::string courant_option() const override { return kAcousticCfl; }
  // At a free surface the symmetric pressure force's pre-stress tips Wendland C2's square lattice at
  // 3 dx over; the quintic spline at a support of 2.79 dx holds it without elasticity, its flat walls
  // held by the wall bounding (docs/verification/free_surface.md, "The quintic spline's stable window").
  KernelChoice default_kernel(const Physics<D>& phys) const override {
    return phys.free_surface ? KernelChoice{KernelType::QuinticSpline, 0.93} : KernelChoice{};
  }
  std::string options_prefix() const override { return kWcsphPrefix; }
  RenamedOption renamed_option(const std::string& option) const override {
    const RenamedOption own = scheme_operator_rename(kWcsphPrefix, option);
    return own.now.empty() ? acoustic_cfl_rename(option) : own;
  }
  // Measured (docs/performance.md, "Memory per particle").
  double bytes_per_particle() const override { return D == 3 ? 1.6e3 : 0.56e3; }
  double density_at_pressure(double p) const override { return eos_.density(p); }
  void set_from_options() override;
  void setup(Discretisation<D>& disc) override;
  double stable_dt() const override;
  StepReport step(double dt) override;
  nlohmann::json describe() const override;
  nlohmann::json checkpoint_scalars() const override { return {{"energy_budget", energy_.to_json()}}; }
  void restore_scalars(const nlohmann::json& j) override {
    energy_.from_json(j.value("energy_budget", nlohmann::json()));
  }
  const EnergyBudget* energy_budget() const override { return &energy_; }
  EnergyBudget* energy_budget() override { return &energy_; }

 private:
  void sum_densities();
  void remove_viscous_smoothing_error(const std::vector<LaplacianCorrection<D>>& factors,
                                      const std::vector<Vector<D>>& lap_u, std::vector<Vector<D>>* viscous_part);
  void apply_corrected_forms(const std::vector<Tensor<D>>& M, const std::vector<Vector<D>>& grad_p,
                             const std::vector<Tensor<D>>& grad_u);
  void add_body_force_and_limit();
  // A rate part's field, set to `zero` over the owned particles; null where the part's cause is off.
  template <class T> std::vector<T>* zeroed(FieldId<T> id, const T& zero) {
    if (!id.valid()) return nullptr;
    std::vector<T>& f = disc_->particles.fields[id];
    f.assign(disc_->particles.n_owned, zero);
    return &f;
  }
  void declare_energy_budget(const Discretisation<D>& disc);
  void set_start_state(Discretisation<D>& disc);
  void resolve_choices(const Discretisation<D>& disc);
  // Credits a kick u -> u + dt/2 a, rho -> rho + dt/2 drho with the current rates to their causes.
  void credit_kick(double half_dt, const std::vector<Vector<D>>& u, const std::vector<double>& rho);
  // The step's phases (step()).
  void kick_drift_rates_kick(double dt);
  void shift(double dt);
  // Accelerations and density rates at the current positions, velocities and densities.
  void compute_rates();
  // The density diffusion's fields beside the densities: Antuono's gradient, the particle-scale part.
  struct DiffusionFields {
    std::vector<Vector<D>> grad_rho;
    std::vector<double> rho_fine;
  };
  DiffusionFields densities_and_pressures();
  wcsph::RateForms rate_forms() const;
  void sum_rates(const wcsph::RatesInputs<D>& in);
  void update_pressure();
  // The largest speed whose square sets a pressure scale of the scene; c0 = c0_factor times it.
  double speed_scale();
  // Removes the fluid's net volume rate from the density rates (closed or periodic scenes).
  void remove_net_volume_rate();

  Discretisation<D>* disc_ = nullptr;
  wcsph::TaitEos eos_;
  wcsph::MonaghanAV av_;
  PetscReal c0_factor_ = 10.0;  // c0 = factor * U_ref unless -c0 is given
  PetscReal c0_ = 0.0;
  PetscReal cfl_ = 0.25;
  PetscReal delta_ = 0.1;
  DensityMethod density_ = DensityMethod::Continuity;
  DensityDiffusion diffusion_ = DensityDiffusion::Molteni;
  bool diffusion_chosen_ = false;  // -density_diffusion given: no default by the scene's physics
  OperatorSet operators_ = OperatorSet::Consistent;
  // Second: at c0 = 10 U the second-order term's deficit offsets the weakly compressible model's own
  // dissipation (docs/verification/speed_against_error.md).
  ViscousLaplacian viscous_laplacian_ = ViscousLaplacian::Second;
  WcsphGradient gradient_ = WcsphGradient::Auto;
  LindShifting shifting_model_;
  FreeSurface<D> free_surface_;
  // The leapfrog carries the last accelerations and density rates into the next step: particle fields.
  FieldId<Vector<D>> acc_;
  FieldId<double> drho_;
  // Their parts by cause, declared where the cause acts: the energy budget credits each kick with them.
  FieldId<Vector<D>> viscous_acc_, av_acc_;
  FieldId<double> diffusion_rate_;
  EnergyBudget energy_;  // since the run's start (kept in checkpoints)
  double max_acc_ = 0.0;
  bool walls_ = false;
  bool extrapolated_ = false;  // walls or inlets: pressures extrapolated from the fluid (update_pressure)
  OutletPressure outlet_pressure_ = OutletPressure::Transmissive;  // -outlet_pressure
  PetscReal outlet_relaxation_ = 0.25;                             // -outlet_relaxation: sigma
  std::string speed_scale_name_;
  int closed_volume_option_ = -1;      // -closed_volume: -1 unset (on without a free surface), 0 off, 1 on
  bool prepared_start_ = false;        // -prepared_start: the case's slow-manifold velocity added at set-up
  bool diffusion_at_surface_ = false;  // -density_diffusion_at_surface
  int wall_bounding_option_ = -1;      // -wall_bounding: -1 unset (on with a free surface), 0 off, 1 on
  WallPressure wall_pressure_ = WallPressure::Adami;  // -wall_pressure
  bool bound_to_walls_ = false;
  WallBounding<D> wall_bounding_;
  long bounded_ = 0;  // fluid particles put back on a wall's face, summed over the steps
  // This step's free-surface particles (owned), found once at the rates' positions and used again by
  // the shift, which comes at the same positions; and as flags on owned and ghost particles.
  std::vector<char> surface_;
  std::vector<double> surface_flags_;
  bool closed_volume_ = false;
};

}  // namespace sph
