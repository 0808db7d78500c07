#pragma once
// Options every scene with wall layers shares, read inside the case's own options block (so -help
// lists them under the case) and checked after it.
#include <petscsys.h>

#include "src/core/option_reads.hpp"
#include "src/core/options.hpp"

namespace sph {

inline PetscErrorCode read_wall_scene_options(PetscOptionItems* PetscOptionsObject, PetscInt* layers, PetscReal* rho0) {
  PetscFunctionBeginUser;
  PetscCall(option_real(PetscOptionsObject, "-rho0", "Density", *rho0, rho0, nullptr));
  PetscCall(option_int(PetscOptionsObject, "-wall_layers", "Layers of wall particles (must cover the kernel support)",
                       *layers, layers, nullptr));
  PetscFunctionReturn(0);
}

inline void check_wall_scene_options(PetscInt layers, PetscReal rho0) {
  require(rho0 > 0, "-rho0", "positive", rho0);
  require(layers >= 1, "-wall_layers", "at least 1", layers);
}

}  // namespace sph
