#include "src/run/run_control.hpp"

#include <sstream>

#include "src/core/error.hpp"
#include "src/core/option_reads.hpp"
#include "src/core/options.hpp"
#include "src/run/threads.hpp"

namespace sph {

namespace {
constexpr PetscInt kMaxCheckpointsKept = 1000;
const char* const box_exit_names[] = {"stop", "remove", "auto"};
const char* const body_pressure_force_names[] = {"surface", "pairs"};
const char* const output_times_names[] = {"step", "exact"};

// What becomes of fluid that leaves the box, and the start's perturbation (round-off studies).
PetscErrorCode read_box_exit_and_start_options(PetscOptionItems* PetscOptionsObject, RunControl* o) {
  PetscFunctionBeginUser;
  PetscCall(option_choice(PetscOptionsObject, "-box_exit",
                          "Fluid beyond a side of the box that is not periodic: auto (taken out of the run and "
                          "counted where it left through a side no wall covers, a splash thrown out of an open "
                          "tank; the run stops where it went through a wall), stop (the run stops and names the "
                          "particle) or remove (always taken out and counted)",
                          box_exit_names, 3, box_exit_names[o->box_exit], &o->box_exit, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-start_perturbation",
                        "Move each fluid particle's start by a random amount up to this fraction of dx along "
                        "each axis (0: none; 1e-12 asks whether round-off moves the answer)",
                        o->start_perturbation, &o->start_perturbation, nullptr, OptionLevel::expert));
  PetscCall(option_int(PetscOptionsObject, "-start_seed",
                       "Seed of -start_perturbation's random moves (each particle's move depends on it and the "
                       "particle's id only, not on the ranks)",
                       o->start_seed, &o->start_seed, nullptr, OptionLevel::expert));
  PetscFunctionReturn(0);
}

// Where the frames go, what they hold and when they are written.
PetscErrorCode read_output_options(PetscOptionItems* PetscOptionsObject, RunControl* o) {
  PetscFunctionBeginUser;
  PetscCall(option_real(PetscOptionsObject, "-output_interval",
                        "Time between VTK frames (-1: t_end/20, 0: first and last only)", o->output_interval,
                        &o->output_interval, nullptr));
  PetscCall(option_choice(PetscOptionsObject, "-output_times",
                          "When frames are written: step (at the first step that reaches each multiple of "
                          "-output_interval, the steps as the stability limits make them) or exact (the steps "
                          "before each frame evened out to land on its time, as they land on -t_end: the run then "
                          "takes other steps than one with other frame times)",
                          output_times_names, 2, output_times_names[o->exact_output_times], &o->exact_output_times,
                          nullptr));
  PetscCall(option_string(PetscOptionsObject, "-output_dir",
                          "Output directory (default out/<case>-<solver>-<nx>; with -restart, the checkpoint's folder)",
                          o->output_dir, o->output_dir, sizeof(o->output_dir), nullptr));
  PetscCall(option_string(PetscOptionsObject, "-output_fields",
                          "Extra point arrays in the VTK frames: vorticity (the solver's own fields, e.g. ISPH's "
                          "free_surface, are always written)",
                          o->output_fields, o->output_fields, sizeof(o->output_fields), nullptr));
  PetscFunctionReturn(0);
}

PetscErrorCode read_options(RunControl* o) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(PETSC_COMM_WORLD, nullptr, "Run control and output", "sph");
  PetscCall(option_real(PetscOptionsObject, "-t_end", "End time", o->t_end, &o->t_end, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-dt", "Fixed time step (0: from the solver's stability limits)", o->dt,
                        &o->dt, nullptr));
  PetscCall(option_bool(PetscOptionsObject, "-dt_force",
                        "Run a -dt above the stability limit instead of refusing it (recorded in summary.json)",
                        o->dt_force, &o->dt_force, nullptr));
  PetscCall(option_int(PetscOptionsObject, "-max_steps", "Stop after this many steps (-1: no limit)", o->max_steps,
                       &o->max_steps, nullptr));
  PetscCall(read_output_options(PetscOptionsObject, o));
  PetscCall(option_bool(PetscOptionsObject, "-wall_forces",
                        "Write the force and moment on every body and on the walls to timeseries.csv each step "
                        "(force_<body>_x, ..., moment_<body>; pressure and viscous parts)",
                        o->wall_forces, &o->wall_forces, nullptr));
  PetscCall(option_choice(PetscOptionsObject, "-body_pressure_force",
                          "A body's pressure force: surface (the pressure fitted at its surface's faces and "
                          "integrated over them, so a uniform pressure gives none; bodies of YAML scenes, a plate's "
                          "faces each from its own side) or pairs (summed over the wall-fluid pairs, as for the "
                          "walls and the bodies of .vtp scenes)",
                          body_pressure_force_names, 2, body_pressure_force_names[o->body_pressure_force],
                          &o->body_pressure_force, nullptr));
  PetscCall(
      option_real(PetscOptionsObject, "-free_body_added_mass",
                  "Free bodies: the added mass the coupling anticipates, in units of the fluid mass the body "
                  "displaces (-1: the scheme's, 1 for ISPH, whose pressure answers a body's acceleration at once, "
                  "0 for the explicit schemes); a state at rest does not depend on it "
                  "(docs/verification/free_bodies.md)",
                  o->free_body_added_mass, &o->free_body_added_mass, nullptr));
  PetscCall(option_bool(PetscOptionsObject, "-overwrite",
                        "Replace the run already in -output_dir (its frames, tables, summary, checkpoint)",
                        o->overwrite, &o->overwrite, nullptr));
  PetscCall(
      option_real(PetscOptionsObject, "-neighbour_skin",
                  "Verlet-list skin as a fraction of the kernel support (-1: the solver's, 0.1 for ISPH, "
                  "0.2 for the explicit schemes; a wider skin rebuilds the lists less often and holds more pairs)",
                  o->skin, &o->skin, nullptr, OptionLevel::expert));
  PetscCall(option_real(PetscOptionsObject, "-steady_tol",
                        "Stop when |dKE/dt| / KE over the last time unit falls below this (0: run to t_end; "
                        "-1: the case's default)",
                        o->steady_tol, &o->steady_tol, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-checkpoint_interval",
                        "Time between checkpoints (<output_dir>/checkpoint.bin; -1: with every frame, 0: never)",
                        o->checkpoint_interval, &o->checkpoint_interval, nullptr));
  PetscCall(option_int(PetscOptionsObject, "-checkpoints_kept",
                       "Checkpoints kept: the newest is checkpoint.bin, the one before it checkpoint.bin.1, and "
                       "so on (to go back to before a blow-up)",
                       o->checkpoints_kept, &o->checkpoints_kept, nullptr, OptionLevel::expert));
  PetscCall(option_int(PetscOptionsObject, "-partition_interval",
                       "Steps between re-orderings of the particles along a space-filling curve, which also "
                       "re-balances them over MPI ranks (0: only at start-up)",
                       o->partition_interval, &o->partition_interval, nullptr, OptionLevel::expert));
  PetscCall(option_int(PetscOptionsObject, "-threads",
                       "OpenMP threads per MPI rank for the pair loops, neighbour search and PPE assembly (0: "
                       "OMP_NUM_THREADS if set, else this rank's cores shared with the other ranks on the node)",
                       o->threads, &o->threads, nullptr));
  PetscCall(option_string(PetscOptionsObject, "-restart", "Resume from this checkpoint (same case, solver and options)",
                          o->restart, o->restart, sizeof(o->restart), nullptr));
  PetscCall(option_bool(PetscOptionsObject, "-progress", "Print a progress line on stderr about once a second",
                        o->progress, &o->progress, nullptr));
  PetscCall(read_box_exit_and_start_options(PetscOptionsObject, o));
  PetscCall(option_bool(PetscOptionsObject, "-check_ghosts",
                        "Check before every pair loop that the ghost copies hold their owners' values, and stop "
                        "at a stale one (an internal error: for developers and bug reports; on in debug builds)",
                        o->check_ghosts, &o->check_ghosts, nullptr, OptionLevel::expert));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}
}  // namespace

void read_run_control_block() {
  RunControl control;
  SPH_PETSC(read_options(&control));
}

void read_run_control(RunControl& opt, double case_steady_tol, int dim) {
  SPH_PETSC(read_options(&opt));
  require(opt.t_end > 0, "-t_end", "positive", opt.t_end);
  require(opt.dt >= 0, "-dt", "non-negative", opt.dt);
  require(opt.max_steps >= -1, "-max_steps", "-1 (no limit) or non-negative", opt.max_steps);
  require(opt.output_interval == -1 || opt.output_interval >= 0, "-output_interval",
          "-1 (t_end/20), 0 (first and last frame) or positive", opt.output_interval);
  // Each kept checkpoint is a full copy of the state, and each write moves them all along.
  require(opt.checkpoints_kept >= 1 && opt.checkpoints_kept <= kMaxCheckpointsKept, "-checkpoints_kept",
          "between 1 and " + std::to_string(kMaxCheckpointsKept), static_cast<double>(opt.checkpoints_kept));
  require(opt.checkpoint_interval == -1 || opt.checkpoint_interval >= 0, "-checkpoint_interval",
          "-1 (with every frame), 0 (never) or positive", opt.checkpoint_interval);
  require(opt.steady_tol == -1 || opt.steady_tol >= 0, "-steady_tol", "-1 (the case's default), 0 (off) or positive",
          opt.steady_tol);
  require(opt.skin == -1 || (opt.skin >= 0 && opt.skin <= 1), "-neighbour_skin", "-1 (the solver's) or in [0, 1]",
          opt.skin);
  require(opt.partition_interval >= 0, "-partition_interval", "non-negative", opt.partition_interval);
  require(opt.threads >= 0, "-threads", "non-negative", opt.threads);
  require(opt.start_perturbation >= 0 && opt.start_perturbation < 0.5, "-start_perturbation", "in [0, 0.5)",
          opt.start_perturbation);
  opt.threads = configure_threads(static_cast<int>(opt.threads));
  ghost_checks() = opt.check_ghosts;
  std::stringstream fields(opt.output_fields);
  for (std::string f; std::getline(fields, f, ',');) {
    if (f != "vorticity") throw Error("-output_fields takes vorticity (got '" + f + "')");
    if (dim == 1) throw Error("-output_fields vorticity needs a 2D or 3D scene");
    opt.vorticity_output = true;
  }
  if (opt.output_interval < 0) opt.output_interval = opt.t_end / 20;
  if (opt.steady_tol < 0) opt.steady_tol = case_steady_tol;
}

}  // namespace sph
