#include "src/run/interrupt.hpp"

#include <petscsys.h>
#include <unistd.h>

#include <csignal>

namespace sph {

namespace {
volatile std::sig_atomic_t g_signal = 0;

extern "C" void record_signal(int sig) {
  if (g_signal != 0) {
    std::signal(sig, SIG_DFL);  // the second one: leave now, the default way
    std::raise(sig);
    return;
  }
  g_signal = sig;
}
}  // namespace

void install_interrupt_handlers() {
  struct sigaction action {};
  action.sa_handler = record_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;  // system calls in progress (file writes, MPI) go on
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  sigaction(SIGHUP, &action, nullptr);  // a closed terminal: end as cleanly as a batch system's SIGTERM
  // Output to a closed pipe (sph ... | head) must not end the run: the write fails, the run goes on.
  std::signal(SIGPIPE, SIG_IGN);
}

std::string signal_name(int signal) {
  if (signal == SIGINT) return "SIGINT";
  if (signal == SIGTERM) return "SIGTERM";
  if (signal == SIGHUP) return "SIGHUP";
  return "signal " + std::to_string(signal);
}

int interrupt_requested() {
  int mine = static_cast<int>(g_signal), any = 0;
  MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
  return any;
}

}  // namespace sph
