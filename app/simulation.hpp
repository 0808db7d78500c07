#pragma once
// The sph program's wiring: picks the case and the solver by name, reads the run's options and hands
// them to the time loop (src/run/time_loop.hpp).
#include <string>

namespace sph {

struct RunOptions {
  std::string case_name = "taylor_green";
  std::string solver_name = "isph";
};

// Prints every component's options (for -help).
void print_all_options(int dim);

// Runs the case with the solver in dimension `dim`; throws sph::Error on bad input or a failed run
// (after writing the failed run's summary and keeping the last good output).
void run_simulation(const RunOptions& opts, int dim);

}  // namespace sph
