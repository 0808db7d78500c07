#pragma once
// A case (what -case runs): initial particles, the box, the physics it needs, and (where one exists)
// the reference solution its errors are measured against. Cases use core types only.
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "src/boundary/moving_bodies.hpp"
#include "src/boundary/open_boundaries.hpp"
#include "src/core/domain.hpp"
#include "src/core/physics.hpp"
#include "src/io/surface_writer.hpp"
#include "src/particles/particles.hpp"
#include "src/run/probes.hpp"

namespace sph {

template <int D> class Case {
 public:
  virtual ~Case() = default;
  virtual std::string name() const = 0;
  // The default output folder's stem, out/<output_name>-<solver>-<resolution> (a scene file's adds its name).
  virtual std::string output_name() const { return name(); }

  // Reads the case's options (PETSc options block) and checks their values (throws sph::Error).
  virtual void set_from_options() = 0;

  // Owned particles of this rank (the whole scene on one rank) and the box.
  virtual void create(Particles<D>& P, Domain<D>& domain) const = 0;
  // How many particles create() makes at least, counted without making them (0: not known before): the
  // memory check refuses a scene too large for the machine before it allocates (src/run/memory_budget.hpp).
  virtual double minimum_particles() const { return 0.0; }
  virtual double spacing() const = 0;  // initial particle spacing dx
  virtual int resolution() const = 0;  // particles per unit length label (nx)
  virtual Physics<D> physics() const = 0;
  virtual double default_t_end() const = 0;

  // Error norms against the reference at time t, reduced over all ranks; empty without a reference.
  virtual std::map<std::string, double> errors(const Particles<D>& P, double t) const { return {}; }
  // Why the error norm `name` of the last errors() call is NaN (it could not be measured), for
  // summary.json; empty when the case gives no reason.
  virtual std::string unmeasured_reason(const std::string& name) const { return ""; }

  // Named bodies: fixed walls whose force and moment timeseries.csv reports (src/run/wall_groups.hpp).
  // body_of_particles() gives, by particle id (the order create() makes the particles in, over all
  // ranks), the body's index in body_names(), or -1; empty when no particle is in a body.
  virtual std::vector<std::string> body_names() const { return {}; }
  virtual std::vector<int> body_of_particles() const { return {}; }
  // Each body's prescribed motion, in the order of body_names() (empty: all fixed).
  virtual std::vector<PrescribedMotion<D>> body_motions() const { return {}; }
  // Per body, in the same order: its free state where the fluid moves it (src/boundary/free_body.hpp),
  // inactive where its motion is prescribed (empty: none free).
  virtual std::vector<FreeBody<D>> free_bodies() const { return {}; }
  // By particle id, 1 for a free-slip wall particle (no shear: src/boundary/moving_bodies.hpp); empty
  // when every wall is no-slip.
  virtual std::vector<char> free_slip_of_particles() const { return {}; }
  // By particle id, the form of pressure continuation a wall particle's group chose (a WallPressure,
  // src/boundary/adami_wall_model.hpp; -1: -wall_pressure's); empty when no group chose one.
  virtual std::vector<signed char> wall_pressure_of_particles() const { return {}; }
  // Inlets and outlets (src/boundary/open_boundaries.hpp; empty: none). Their buffer particles are
  // among create()'s, kinds kInlet and kOutlet.
  virtual std::vector<OpenBoundary<D>> open_boundaries() const { return {}; }
  // Each body's surface at t = 0, for ParaView (empty: none).
  virtual std::vector<SurfaceMesh> body_surfaces() const { return {}; }
  // Points whose pressure timeseries.csv reports every step (src/run/probes.hpp; empty: none).
  virtual std::vector<Probe<D>> probes() const { return {}; }

  // Thickness of the wall-particle layers (0 without walls): the kernel support must fit in it.
  virtual double wall_thickness() const { return 0.0; }
  // The one-line refusal when wall_thickness() is below the kernel support (both in units of dx).
  virtual std::string thin_walls(double thickness_dx, double support_dx) const {
    return "wall layers (" + std::to_string(thickness_dx) + " dx) are thinner than the kernel support (" +
           std::to_string(support_dx) + " dx); raise -wall_layers or lower -h_over_dx";
  }
  // Relative kinetic-energy change per unit time below which the flow counts as steady and the run
  // stops (0: run to t_end). The -steady_tol option overrides it.
  virtual double steady_tolerance() const { return 0.0; }
  // Time averages a case accumulates over a run (the cavity's centreline profiles): called after every
  // step, before errors(), with the step's end time and length. Their state travels in the checkpoint
  // (accumulated_state() is written, restore_accumulated_state() reads it back on -restart).
  virtual void accumulate(const Particles<D>& P, double t, double dt) {}
  virtual nlohmann::json accumulated_state() const { return nullptr; }
  virtual void restore_accumulated_state(const nlohmann::json& state) {}
  // Case-specific files written at the end of a run (e.g. centreline profiles).
  virtual void write_outputs(const Particles<D>& P, double t, const std::string& dir) const {}
  virtual nlohmann::json parameters() const = 0;
};

}  // namespace sph
