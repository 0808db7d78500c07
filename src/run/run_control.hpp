#pragma once
// Run control: the options of the time loop, its frames and checkpoints, the neighbour search and the
// threads (-t_end, -dt, -output_interval, -restart, ...; `-help` lists them under "Run control").
#include <petscsys.h>

#include <string>

#include "src/neighbours/ghost_check.hpp"

namespace sph {

struct RunControl {
  PetscReal t_end = 1.0;
  PetscReal dt = 0.0;                  // 0: from the solver's stability limits
  PetscInt max_steps = -1;             // -1: no limit
  PetscReal output_interval = -1;      // -1: t_end / 20
  PetscInt exact_output_times = 0;     // 1: steps evened out to land on each frame's time
  PetscReal skin = -1;                 // Verlet skin as a fraction of the support radius; -1: the solver's
  PetscReal steady_tol = -1;           // -1: the case's default
  PetscReal checkpoint_interval = -1;  // -1: with every VTK frame, 0: never
  PetscInt checkpoints_kept = 1;       // checkpoint.bin, then checkpoint.bin.1, ... (older)
  PetscInt partition_interval = 50;    // steps between re-partitions along the space-filling curve
  PetscInt threads = 0;                // OpenMP threads per rank (0: see configure_threads)
  char restart[PETSC_MAX_PATH_LEN] = "";
  PetscBool progress = PETSC_TRUE;
  PetscBool overwrite = PETSC_FALSE;    // replace a run already in output_dir
  PetscBool dt_force = PETSC_FALSE;     // run a -dt above the stability limit anyway
  PetscBool wall_forces = PETSC_TRUE;   // timeseries.csv's force columns (src/run/wall_groups.hpp)
  PetscInt body_pressure_force = 0;     // 0 surface, 1 pairs (src/run/wall_groups.hpp)
  PetscReal free_body_added_mass = -1;  // -1: the scheme's (src/boundary/free_body.hpp)
  // Fluid leaving the box: 0 stop the run, 1 remove it, 2 remove it unless it went through a wall
  // (src/run/box_exit.hpp).
  PetscInt box_exit = 2;
  PetscReal start_perturbation = 0.0;  // fluid starts moved by up to this fraction of dx (round-off studies)
  PetscInt start_seed = 1;
  PetscBool check_ghosts = ghost_checks() ? PETSC_TRUE : PETSC_FALSE;  // src/neighbours/ghost_check.hpp
  char output_dir[PETSC_MAX_PATH_LEN] = "";
  char output_fields[128] = "";   // extra point arrays in the frames: "vorticity"
  bool vorticity_output = false;  // from output_fields

  bool restarting() const { return restart[0] != '\0'; }
};

// Reads the options into `control` (its values are the defaults) and checks them; -1 defaults that
// depend on the case are resolved: the output interval (t_end / 20) and the steady-state tolerance.
void read_run_control(RunControl& control, double case_steady_tol, int dim);

// Reads the options block only (for -help and the unused-option check).
void read_run_control_block();

}  // namespace sph
