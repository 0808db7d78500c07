#pragma once
// The memory check before a run allocates its solver: the solver's measured peak bytes per particle
// times the particles a node holds must fit in the node's memory (the smaller of its physical memory
// and a control-group limit). Three stages:
//  - before the case creates its particles, the count it plans (Case::minimum_particles), so a lattice
//    case too large is refused in a fraction of a second without allocating;
//  - while the case creates its particles, no process may hold more than the whole node could run
//    (Particles::add stops there: -nx 100000 is refused before it fills the memory);
//  - once they are created, the particles of this node's ranks together (check_scene).
#include <cstddef>
#include <string>

namespace sph {

// Bytes of memory of this node: the smaller of the physical memory and a cgroup limit.
double node_memory_bytes();

class MemoryBudgetScope {
 public:
  // `bytes_per_particle`: the solver's peak memory per particle; `scheme`: its name for the message;
  // `planned_particles`: how many the whole scene has at least (0: not known before creating them).
  // Collective on PETSC_COMM_WORLD; throws sph::Error when this node's share of the planned particles
  // cannot fit.
  MemoryBudgetScope(double bytes_per_particle, const std::string& scheme, double planned_particles = 0.0);
  ~MemoryBudgetScope();
  MemoryBudgetScope(const MemoryBudgetScope&) = delete;
  MemoryBudgetScope& operator=(const MemoryBudgetScope&) = delete;

  // Collective on PETSC_COMM_WORLD: throws sph::Error naming the figures when the owned particles of
  // the ranks on this node need more than its memory.
  void check_scene(std::size_t n_owned) const;

 private:
  double bytes_per_particle_, memory_;
  std::string scheme_;
};

}  // namespace sph
