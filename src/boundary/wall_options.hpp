#pragma once
// The wall options both incompressible and weakly compressible schemes read, in their own -help block:
// one text and one default for each, whichever scheme runs.
#include <petscsys.h>

#include "src/boundary/adami_wall.hpp"
#include "src/core/option_reads.hpp"

namespace sph {

struct WallOptions {
  PetscBool bounding, bounding_set;  // -wall_bounding (unset: on with a free surface)
  PetscInt pressure;                 // -wall_pressure, a WallPressure
};

inline PetscErrorCode read_wall_options(PetscOptionItems* block, WallOptions* o) {
  PetscFunctionBeginUser;
  PetscCall(option_bool(block, "-wall_bounding",
                        "Put fluid particles found behind a wall's face back on it, their velocity into the "
                        "wall removed: a stop that only takes energy away, and walls that hold without the "
                        "ripple of the kernel sum over their particles (a flat one, as the quintic spline's at "
                        "-h_over_dx 0.93, lets fluid through; default: on with a free surface)",
                        o->bounding, &o->bounding, &o->bounding_set));
  PetscCall(option_choice(block, "-wall_pressure", wall_pressure_help, wall_pressure_names, 2,
                          wall_pressure_names[o->pressure], &o->pressure, nullptr, OptionLevel::expert));
  PetscFunctionReturn(0);
}

}  // namespace sph
