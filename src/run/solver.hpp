#pragma once
// The interface every scheme implements (one folder per scheme under solvers/). A solver reads its
// options, takes the discretisation once, then advances it by one time step at a time.
#include <nlohmann/json.hpp>
#include <string>

#include "src/boundary/moving_bodies.hpp"
#include "src/boundary/open_boundaries.hpp"
#include "src/boundary/wall_model.hpp"
#include "src/core/error.hpp"
#include "src/core/options.hpp"
#include "src/core/physics.hpp"
#include "src/io/checkpoint.hpp"
#include "src/io/particle_writer.hpp"
#include "src/kernels/kernel.hpp"
#include "src/kernels/kernel_options.hpp"
#include "src/neighbours/neighbourhood.hpp"
#include "src/sph/energy_budget.hpp"

namespace sph {

// What a step reports beyond the new particle state (linear solver figures, for implicit schemes).
struct StepReport {
  int linear_iterations = -1;  // -1: no linear solve in this scheme
  int linear_reason = 0;       // PETSc KSPConvergedReason
  double linear_residual = 0.0;
};

// The discretised problem a solver works on: the particles, their neighbourhood, the kernel, the
// physics and the spacing. Owned by the time loop (RunState), outliving the solver's steps. (A
// "scene" is a particle file or a YAML scene read by -case scene; a "case" is any problem definition.)
template <int D> struct Discretisation {
  Particles<D>& particles;
  Neighbourhood<D>& neighbourhood;
  const Kernel<D>& kernel;
  Physics<D> physics;
  double dx;  // initial particle spacing
  // Bodies with prescribed motion; the solvers move them at their drift (src/boundary/moving_bodies.hpp).
  MovingBodies<D> bodies = {};
  // Inlets and outlets; the solvers drift their buffers (src/boundary/open_boundaries.hpp).
  OpenBoundaries<D> open = {};
  // The walls' boundary model, as the scheme's options chose it at setup (src/boundary/wall_model.hpp);
  // null for a scheme without walls. The force on wall groups reads it too.
  std::shared_ptr<const WallModel<D>> walls = {};
};

// A case that asks for a model the solver does not have is refused, not silently run without it.
template <int D>
void refuse_unmodelled(const Physics<D>& phys, const std::string& solver, bool gas, bool external_force) {
  if (phys.is_gas() && !gas)
    throw Error("this case is a compressible gas (ideal-gas EOS, energy equation): use -solver compressible, not " +
                solver);
  if (phys.has_external_force() && !external_force)
    throw Error("this case needs a position-dependent body force, which -solver " + solver +
                " does not model; use -solver compressible");
}

// Inlets and outlets (src/boundary/open_boundaries.hpp) are built for the liquid schemes; with a free
// surface an outlet keeps a water level (its pressure hydrostatic below it): a scheme or a scene beyond
// that is refused, not run with a buffer it does not model.
template <int D>
void refuse_unmodelled_open_boundaries(const Discretisation<D>& disc, const std::string& solver, bool modelled) {
  if (!disc.open.any()) return;
  if (!modelled)
    throw Error("-solver " + solver + " has no inlets or outlets; use -solver isph or wcsph, or close the scene");
  const Vector<D>& g = disc.physics.gravity;
  for (const OpenBoundary<D>& b : disc.open.boundaries())
    if (b.keeps_level && (g.norm() == 0 || g[b.axis] != 0 || g.cwiseAbs().maxCoeff() != g.norm()))
      throw Error(
          "a level-keeping outlet needs gravity along an axis across it (the level is a height above its "
          "bed); give gravity along one axis, not along the outlet's, or drop level");
  if (!disc.physics.free_surface) return;
  for (const OpenBoundary<D>& b : disc.open.boundaries())
    if (b.type == OpenBoundary<D>::Type::Outlet && !(b.keeps_level && disc.physics.gravity.norm() > 0))
      throw Error(
          "an outlet in a free-surface scene needs the water level it keeps (and gravity); add level: H to "
          "the outlet, or give free_surface: false");
}

template <int D> class Solver {
 public:
  virtual ~Solver() = default;
  virtual std::string name() const = 0;
  // Reads the solver's options (PETSc options block; -help lists them) and checks them.
  virtual void set_from_options() = 0;
  // Options PETSc reads for this solver only during its steps (a linear solve's viewers, sub-solver
  // options), named without the dash: checked after the first step rather than at start-up.
  virtual bool reads_late(const std::string&) const { return false; }
  // The name now of an option this solver once read under another (without the dash): a run given the
  // old one is told the new one (see check_unused_options).
  virtual RenamedOption renamed_option(const std::string&) const { return {}; }
  // The prefix of the options that are its own where another scheme reads the same word (without the
  // dash; src/sph/operator_options.hpp), or "".
  virtual std::string options_prefix() const { return ""; }
  // The kernel and h of a run that gives neither -kernel nor -h_over_dx (src/kernels/kernel_options.hpp).
  virtual KernelChoice default_kernel(const Physics<D>&) const { return {}; }
  // The option that sets its Courant number (src/sph/step_limits.hpp): failure messages name it.
  virtual std::string courant_option() const = 0;
  virtual void setup(Discretisation<D>& disc) = 0;
  // Largest time step the scheme's stability limits allow for the current state.
  virtual double stable_dt() const = 0;
  virtual StepReport step(double dt) = 0;
  // Peak memory of a run per particle, measured (docs/performance.md, "Memory per particle"): the
  // memory check refuses a run that cannot fit before it is allocated (src/run/memory_budget.hpp).
  virtual double bytes_per_particle() const = 0;
  // The density of a fluid particle at pressure p, for the particles an outlet takes over (they hold
  // the outlet's pressure): the reference density where the scheme is incompressible.
  virtual double density_at_pressure(double p) const = 0;
  // Default Verlet skin (-neighbour_skin) as a fraction of the support: a wider one rebuilds the lists
  // less often and holds more pairs (docs/performance.md, "Memory per particle").
  virtual double neighbour_skin() const { return 0.2; }
  // The added mass a free body's coupling anticipates, in units of the fluid mass it displaces
  // (src/boundary/free_body.hpp): none where the pressure answers the body's motion through sound.
  virtual double free_body_added_mass() const { return 0.0; }
  // Active models and their parameters, linear solver settings: goes into summary.json.
  virtual nlohmann::json describe() const = 0;

  // Scalars beyond the particles that a restart needs to continue exactly; restored after setup().
  // Per-particle state is declared in setup() as the particles' fields (Particles::fields, kCarried to
  // follow the particle into checkpoints and migration, kWritten for the frames).
  virtual nlohmann::json checkpoint_scalars() const { return nlohmann::json::object(); }
  virtual void restore_scalars(const nlohmann::json&) {}
  // The scheme's energy budget (src/sph/energy_budget.hpp), null where it keeps none; the time loop
  // writes its columns and credits the fluid it takes out of the box.
  virtual const EnergyBudget* energy_budget() const { return nullptr; }
  virtual EnergyBudget* energy_budget() { return nullptr; }
};

}  // namespace sph
