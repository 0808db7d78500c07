#pragma once
// How many particles this process may create before the run's memory estimate exceeds the memory
// the machine gives it (src/run/memory_budget.hpp sets it from the solver's measured bytes per
// particle). Particles::add refuses past it, so a scene far too large (-nx 100000) stops with one
// line naming the figures before it fills the memory, instead of being killed by the kernel.
#include <cstddef>
#include <limits>
#include <string>

#include "src/core/error.hpp"

namespace sph {

struct ParticleBudget {
  std::size_t limit = std::numeric_limits<std::size_t>::max();
  std::string refusal;  // the one-line message when the limit is reached
};

// One per process: the memory it guards is the process's.
inline ParticleBudget& particle_budget() {
  static ParticleBudget budget;
  return budget;
}

[[noreturn]] inline void refuse_over_budget() { throw Error(particle_budget().refusal); }

}  // namespace sph
