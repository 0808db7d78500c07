#pragma once
// Particle storage shared by every solver: one array per field (structure of arrays).
// Indices [0, n_owned) are the particles this rank owns and integrates; [n_owned, size()) are ghost
// copies (periodic images, and on several ranks the halo of neighbouring ranks) that only supply
// neighbour data. Ghosts are (re)made by the Halo; solvers never write to them directly.
#include <vector>

#include "src/core/types.hpp"
#include "src/particles/field_registry.hpp"
#include "src/particles/particle_budget.hpp"

namespace sph {

// Inlet and outlet particles fill the buffers of open boundaries (src/boundary/open_boundaries.hpp).
enum ParticleKind : int { kFluid = 0, kWall = 1, kInlet = 2, kOutlet = 3 };

// The particles whose pressure is extrapolated from the fluid's (Adami et al. 2012): walls, and the
// inlets' buffers (their velocity is given, their pressure gradient the fluid's).
inline bool extrapolates_pressure(int kind) { return kind == kWall || kind == kInlet; }

template <int D> struct Particles {
  std::size_t n_owned = 0;
  std::size_t n_ghost = 0;
  GlobalIndex n_global = 0;   // all ranks together
  GlobalIndex first_gid = 0;  // global index of owned particle 0; owned gids are contiguous

  std::vector<Vector<D>> x, v;    // position, velocity
  std::vector<double> m, rho, p;  // mass, density, pressure
  std::vector<int> kind;          // ParticleKind
  // gid: the particle's current global index (PETSc row): owned particles of rank r are numbered
  // contiguously after those of ranks < r, and renumbered whenever particles migrate.
  // id: the particle's permanent label (its first gid), for output and checkpoints.
  // A ghost carries its source's gid and id.
  std::vector<GlobalIndex> gid, id;
  // The schemes' own per-particle state, declared by name (field_registry.hpp), sized with the above.
  FieldRegistry<D> fields;

  std::size_t size() const { return n_owned + n_ghost; }

  // Appends an owned particle; only valid before ghosts exist.
  void add(const Vector<D>& pos, const Vector<D>& vel, double mass, double density, double pressure = 0.0,
           int k = kFluid) {
    if (x.size() >= particle_budget().limit) refuse_over_budget();
    x.push_back(pos);
    v.push_back(vel);
    m.push_back(mass);
    rho.push_back(density);
    p.push_back(pressure);
    kind.push_back(k);
    gid.push_back(0);
    id.push_back(-1);  // labelled by assign_global_indices
    fields.push_back();
    ++n_owned;
  }

  // Resizes every field to n_owned + ng (ghost slots are filled by the Halo).
  void set_ghost_count(std::size_t ng) {
    n_ghost = ng;
    const std::size_t n = size();
    x.resize(n), v.resize(n), m.resize(n), rho.resize(n), p.resize(n), kind.resize(n), gid.resize(n), id.resize(n);
    fields.resize(n);
  }
};

}  // namespace sph
