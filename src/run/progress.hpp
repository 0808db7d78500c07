#pragma once
// One progress line on stderr at most about once a second: step, time, dt, linear iterations, ETA.
#include <petscsys.h>

#include <chrono>

namespace sph {

class Progress {
 public:
  Progress(bool enabled, double t_end) : enabled_(enabled), t_end_(t_end), start_(clock::now()), last_(start_) {}

  void update(long step, double t, double dt, int linear_its) {
    if (!enabled_) return;
    const auto now = clock::now();
    if (std::chrono::duration<double>(now - last_).count() < 1.0) return;
    last_ = now;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const double eta = t > 0 ? elapsed * (t_end_ - t) / t : 0.0;
    if (linear_its >= 0)
      PetscFPrintf(PETSC_COMM_WORLD, stderr,
                   "step %6ld  t %.4g/%.4g (%3.0f%%)  dt %.3e  ksp %3d  elapsed %.0fs  ETA %.0fs\n", step, t, t_end_,
                   100.0 * t / t_end_, dt, linear_its, elapsed, eta);
    else
      PetscFPrintf(PETSC_COMM_WORLD, stderr, "step %6ld  t %.4g/%.4g (%3.0f%%)  dt %.3e  elapsed %.0fs  ETA %.0fs\n",
                   step, t, t_end_, 100.0 * t / t_end_, dt, elapsed, eta);
  }

  void done(long steps, double t) {
    if (!enabled_) return;
    const double elapsed = std::chrono::duration<double>(clock::now() - start_).count();
    PetscFPrintf(PETSC_COMM_WORLD, stderr, "done: %ld steps to t = %.4g in %.2f s\n", steps, t, elapsed);
  }

 private:
  using clock = std::chrono::steady_clock;
  bool enabled_;
  double t_end_;
  clock::time_point start_, last_;
};

}  // namespace sph
