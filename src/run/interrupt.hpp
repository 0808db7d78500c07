#pragma once
// SIGINT, SIGTERM and SIGHUP end a run cleanly: the handler only records the signal; the time loop asks
// after each step, all ranks together, and stops at the same step on every rank to write a
// checkpoint, a frame and summary.json before exiting with the conventional code (128 + signal).
#include <string>

namespace sph {

// Thrown by the driver after an interrupted run has written its outputs; main() prints the message
// and exits with 128 + signal (130 for SIGINT, 143 for SIGTERM, 129 for SIGHUP).
struct Interrupted {
  int signal;
  std::string message;
};

// "SIGINT", "SIGTERM", "SIGHUP" or "signal N".
std::string signal_name(int signal);

// Replaces PETSc's handlers for SIGINT, SIGTERM and SIGHUP with one that records the signal (a second
// such signal ends the process at once, as an impatient user expects) and ignores SIGPIPE.
void install_interrupt_handlers();

// The signal number received by any rank so far, 0 if none. Collective on PETSC_COMM_WORLD.
int interrupt_requested();

}  // namespace sph
