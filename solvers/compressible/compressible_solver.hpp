#pragma once
// Compressible SPH for an ideal gas (-solver compressible): the scheme of Springel & Hernquist (2002)
// and Price (2012, JCP 231:759) on the shared kernels and neighbour search.
//   - variable smoothing lengths rho_i h_i^D = m_i eta^D, solved per particle by Newton-Raphson
//     together with the density summation; grad-h factors Omega_i in momentum and energy equations;
//   - P = (gamma - 1) rho u with the thermal energy equation, or (scenes declared isentropic) the
//     entropy function A = P / rho^gamma, constant apart from dissipative heating (Springel & Hernquist 2002);
//   - artificial viscosity: signal-velocity form (Monaghan 1997) or Monaghan (1992) alpha/beta, with
//     optional Balsara (1995) switch and Morris & Monaghan (1997) time-dependent alpha; AV heating;
//   - artificial thermal conductivity (Price 2008);
//   - kick-drift-kick leapfrog (Monaghan 2005, sec. 5.3; Price 2012 sec. 4.6) with a predicted velocity
//     and thermal energy for the velocity-dependent terms;
//   - dt = min_i [C_cour h_i / v_sig,i, C_force sqrt(h_i / |a_i|)].
// Position-dependent external forces come from the scene's Physics (e.g. the toy star's -Omega^2 x).
#include <vector>

#include "solvers/compressible/compressible_iact.hpp"
#include "solvers/compressible/pruned_pairs.hpp"
#include "src/run/solver.hpp"
#include "src/sph/step_limits.hpp"

namespace sph {

enum class ViscositySwitch { None, MorrisMonaghan };

template <int D> class CompressibleSolver : public Solver<D> {
 public:
  std::string name() const override { return "compressible"; }
  std::string courant_option() const override { return kAcousticCfl; }
  RenamedOption renamed_option(const std::string& option) const override { return acoustic_cfl_rename(option); }
  // Measured in 2D; the 3D figure is scaled from WCSPH's, not measured (docs/performance.md,
  // "Memory per particle").
  double bytes_per_particle() const override { return D == 3 ? 2.5e3 : 0.87e3; }
  double density_at_pressure(double) const override { return 0.0; }  // no open boundaries
  void set_from_options() override;
  void setup(Discretisation<D>& disc) override;
  double stable_dt() const override;
  StepReport step(double dt) override;
  nlohmann::json describe() const override;
  // The search radius decides when lists are rebuilt (and positions wrapped): needed for an exact restart.
  nlohmann::json checkpoint_scalars() const override;
  void restore_scalars(const nlohmann::json& j) override;

  // Per-particle state (owned entries), public for tests and diagnostics.
  double total_energy() const;
  Vector<D> total_momentum() const;

 private:
  // h, rho and Omega (and div v, curl v) at the current positions, by Newton-Raphson per particle.
  void solve_density();
  // P, c (and Balsara factors) from rho and the thermal variable; fills ghosts; builds per-particle kernels.
  void update_thermodynamics();
  // Accelerations and rates of the thermal variable and alpha at the current state.
  void compute_forces();
  void ensure_search_radius(double h_max, bool allow_shrink);
  // Re-prunes the pair list at the current positions and smoothing lengths (fills ghost h first).
  void prune_pairs();
  // Whether the pruned list still holds every pair the current smoothing lengths reach.
  bool pairs_valid() const;
  void check_thermal_state() const;

  Discretisation<D>* disc_ = nullptr;
  compressible::ArtificialViscosity av_;
  ViscositySwitch switch_ = ViscositySwitch::None;
  PetscBool balsara_ = PETSC_FALSE;  // Balsara switch on
  PetscBool conductivity_ = PETSC_TRUE;
  PetscReal alpha_u_ = 1.0;
  PetscReal alpha_min_ = 0.1, alpha_max_ = 1.5, mm_sigma_ = 0.1;
  PetscReal eta_ = 0.0;  // 0: the kernel's default
  PetscReal h_tolerance_ = 1e-8;
  PetscReal cfl_ = 0.3, cfl_force_ = 0.25;
  double gamma_ = 1.4;
  bool entropy_ = false;  // thermal variable: A = P/rho^gamma (isentropic scenes) instead of u
  double kappa_ = 2.0;    // kernel support in units of h

  // The particle fields this scheme declares (declare_fields), and references to them for one function.
  struct FieldIds {
    FieldId<double> h, u, thermal, alpha, dthermal, dalpha, vsig;
    FieldId<Vector<D>> acc;
  };
  struct Fields {
    std::vector<double>& h;        // smoothing length (owned + ghost)
    std::vector<double>& u;        // specific internal energy (owned + ghost)
    std::vector<double>& thermal;  // u, or A in entropy mode
    std::vector<double>& alpha;    // viscosity switch (owned + ghost)
    std::vector<Vector<D>>& acc;
    std::vector<double>& dthermal;
    std::vector<double>& dalpha;
    std::vector<double>& vsig;  // signal velocity
  };
  void declare_fields(Particles<D>& P);
  Fields fields() const;
  bool newton_h_step(const Fields& f, const NeighbourList<D>& nl, std::size_t i, int iteration,
                     compressible::HBracket& bracket, bool need_div);
  FieldIds ids_;

  // Per particle (owned + ghost where the pair loop reads neighbours' values).
  std::vector<double> omega_, cs_, balsara_factor_, q_;
  std::vector<Kernel<D>> kernels_;
  compressible::PrunedPairs<D> pairs_;
  long pairs_built_at_rebuild_ = -1;  // the neighbourhood's rebuild count the pruned list belongs to
  // Owned only.
  std::vector<double> divv_, curlv_;

  // Bookkeeping.
  double energy0_ = 0.0;
  Vector<D> momentum0_ = Vector<D>::Zero();
  double momentum_scale0_ = 0.0;
  long density_iterations_max_ = 0, radius_changes_ = 0;
  double h_min_seen_ = 0.0, h_max_seen_ = 0.0;
};

}  // namespace sph
