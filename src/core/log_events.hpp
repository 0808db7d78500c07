#pragma once
// PETSc log events for the phases of a time step, so that the standard -log_view shows where a step's
// time goes next to PETSc's own events (MatAssembly*, KSPSetUp, PCSetUp, KSPSolve, ...).
//
// Every event belongs to the class "SPH"; the time loop runs in its own log stage ("SPH time loop"),
// so -log_view separates set-up from stepping. Times in -log_view are inclusive: an event that runs
// inside another (a forced neighbour rebuild while writing a checkpoint, say) counts in both.
//
// The core's events, shared by every scheme:
//   SPHStep          one solver step (everything below that happens during the step)
//   SPHNbrUpdate     Neighbourhood::update: the displacement check, halo refresh or rebuild
//   SPHNbrRebuild    the rebuild part of it: wrap, halo and Verlet-list build
//   SPHDensity       density and equation of state (a scheme's density or thermodynamic update)
//   SPHForces        pair-loop rates (a scheme's accelerations)
//   SPHShifting      particle shifting with its Taylor corrections
//   SPHDiagnostics   per-step health checks, totals, error norms and the time-series row
//   SPHOutput        VTK frames and the case's output files
//   SPHCheckpoint    checkpoint files
// A scheme registers the events of its own phases with register_log_event (ISPH's SPHPPEAssembly and
// SPHPPESolve, the compressible solver's SPHGasDensityH and SPHGasPairs), next to its code.
#include <petscsys.h>

namespace sph {

enum class LogEvent {
  Step,
  NeighbourUpdate,
  NeighbourRebuild,
  Density,
  Forces,
  Shifting,
  Diagnostics,
  Output,
  Checkpoint,
  Count
};

// The PETSc event id of a core event; the core events (and the stage) are registered on the first
// call, which must come after PetscInitialize.
PetscLogEvent log_event(LogEvent e);
PetscLogStage time_loop_log_stage();

// Registers a scheme's own event (class "SPH") and returns its id; call it once per event, after
// PetscInitialize (a function-local static at the event's first use does both).
PetscLogEvent register_log_event(const char* name);

// Begins the event on construction and ends it on destruction (or at end(), whichever comes first),
// so an exception thrown inside still ends it.
class LogEventScope {
 public:
  explicit LogEventScope(PetscLogEvent e);
  explicit LogEventScope(LogEvent e) : LogEventScope(log_event(e)) {}
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
