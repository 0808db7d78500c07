#pragma once
// The time loop of one run: builds the particles from the case, hands them to the solver, resumes from a
// checkpoint, advances to t_end (or to steady state, or -max_steps) and writes every output: VTK frames,
// timeseries.csv, checkpoints and summary.json. Health checks stop a run that blows up; a failed run
// writes its summary and keeps its last good frame and checkpoint.
#include <functional>
#include <string>

#include "src/kernels/kernel_options.hpp"
#include "src/run/case.hpp"
#include "src/run/run_control.hpp"
#include "src/run/solver.hpp"

namespace sph {

// What a run is made of; the case and the solver have read their options.
template <int D> struct RunParts {
  Case<D>& run_case;
  Solver<D>& solver;
  std::string case_name, solver_name;  // as chosen: the checkpoint's identity and summary.json
  RunControl control;
  KernelChoice kernel;
  std::string output_dir;
  std::function<void()> after_first_step;  // e.g. the check of the options PETSc reads during a step
};

// Throws sph::Error on bad input or a failed run, Interrupted on a signal (after writing a frame, a
// checkpoint and the summary).
template <int D> void run_time_loop(const RunParts<D>& run);

}  // namespace sph
