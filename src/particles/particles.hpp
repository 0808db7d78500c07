#pragma once
// Particle storage shared by every solver: one array per field (structure of arrays).
// Indices [0, n_owned) are the particles this rank owns and integrates; [n_owned, size()) are ghost
// copies (periodic images, and on several ranks the halo of neighbouring ranks) that only supply
// neighbour data. Ghosts are (re)made by the Halo; solvers never write to them directly.
#include <algorithm>
#include <stdexcept>
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

// The columns written on owned particles since their ghost copies were last refreshed: marked by the
// writer (Particles::written), refreshed by the halo before the next pair loop reads them
// (Halo::refresh_stale; docs/developer.md, "Ghosts").
template <int D> struct StaleGhosts {
  bool v = false, m = false, rho = false, p = false;
  std::vector<std::vector<double>*> scalars;  // registry columns
  std::vector<std::vector<Vector<D>>*> vectors;
  bool any() const { return v || m || rho || p || !scalars.empty() || !vectors.empty(); }
};

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

  // The columns whose ghosts are stale (marked by written()).
  StaleGhosts<D> stale;

  std::size_t size() const { return n_owned + n_ghost; }

  // Marks a column as written on the owned particles: its ghost copies are refreshed before the next
  // pair loop (or ghost check) reads them. For the particles' own columns and registry fields; a
  // step-local field is refreshed by its owner (halo().update).
  void written(std::vector<double>& f) {
    if (&f == &m) stale.m = true;
    else if (&f == &rho) stale.rho = true;
    else if (&f == &p) stale.p = true;
    else if (fields.holds(f)) mark(stale.scalars, &f);
    else
      throw std::logic_error(
          "Particles::written: not a particle column; refresh a step-local field with halo().update");
  }
  void written(std::vector<Vector<D>>& f) {
    if (&f == &v) stale.v = true;
    else if (fields.holds(f)) mark(stale.vectors, &f);
    else
      throw std::logic_error(
          "Particles::written: not a particle column; refresh a step-local field with halo().update");
  }

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

 private:
  template <class T> static void mark(std::vector<T*>& marks, T* f) {
    if (std::find(marks.begin(), marks.end(), f) == marks.end()) marks.push_back(f);
  }
};

}  // namespace sph
