#pragma once
// PETSc log events for the phases of a time step, so that the standard -log_view shows where a step's
// time goes next to PETSc's own events (MatAssembly*, KSPSetUp, PCSetUp, KSPSolve, ...).
//
// Every event belongs to the class "SPH"; the time loop runs in its own log stage ("SPH time loop"),
// so -log_view separates set-up from stepping. Times in -log_view are inclusive: an event that runs
// inside another (a forced neighbour rebuild while writing a checkpoint, say) counts in both.
//
//   SPHStep          one solver step (everything below that happens during the step)
//   SPHNbrUpdate     Neighbourhood::update: the displacement check, halo refresh or rebuild
//   SPHNbrRebuild    the rebuild part of it: wrap, halo and Verlet-list build
//   SPHDensity       density/EOS: WCSPH summation and pressure, compressible thermodynamic update
//   SPHGasDensityH   compressible: density and smoothing length by Newton-Raphson (grad-h)
//   SPHGasPairs      compressible: pruned pair lists
//   SPHForces        pair-loop rates: viscous prediction and pressure gradient (ISPH), WCSPH and
//                    compressible accelerations
//   SPHPPEAssembly   ISPH: divergence of u*, free-surface flags and the PPE matrix
//   SPHPPESolve      ISPH: the pressure solve (KSPSolve, whose PCSetUp PETSc logs itself)
//   SPHShifting      particle shifting with its Taylor corrections
//   SPHDiagnostics   per-step health checks, totals, error norms and the time-series row
//   SPHOutput        VTK frames and the case's output files
//   SPHCheckpoint    checkpoint files
#include <petscsys.h>

namespace sph {

enum class LogEvent {
  Step,
  NeighbourUpdate,
  NeighbourRebuild,
  Density,
  GasDensityH,
  GasPairs,
  Forces,
  PpeAssembly,
  PpeSolve,
  Shifting,
  Diagnostics,
  Output,
  Checkpoint,
  Count
};

// The PETSc event id of `e`; the events (and the stage) are registered on the first call, which must
// come after PetscInitialize.
PetscLogEvent log_event(LogEvent e);
PetscLogStage time_loop_log_stage();

// Begins the event on construction and ends it on destruction (or at end(), whichever comes first),
// so an exception thrown inside still ends it.
class LogEventScope {
 public:
  explicit LogEventScope(LogEvent e);
  ~LogEventScope() { end(); }
  LogEventScope(const LogEventScope&) = delete;
  LogEventScope& operator=(const LogEventScope&) = delete;
  void end();

 private:
  PetscLogEvent event_;
  bool open_ = true;
};

// Pushes the time-loop stage for its lifetime.
class TimeLoopLogStage {
 public:
  TimeLoopLogStage();
  ~TimeLoopLogStage();
  TimeLoopLogStage(const TimeLoopLogStage&) = delete;
  TimeLoopLogStage& operator=(const TimeLoopLogStage&) = delete;
};

}  // namespace sph
