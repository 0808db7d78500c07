#pragma once
// Whole-system figures and run-health checks, reduced over all ranks.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "src/core/domain.hpp"
#include "src/core/error.hpp"
#include "src/neighbours/neighbour_list.hpp"
#include "src/particles/global_indices.hpp"

namespace sph {

// Fluid particles only.
template <int D> struct Totals {
  double kinetic_energy = 0.0;
  Vector<D> momentum = Vector<D>::Zero();
  double momentum_scale = 0.0;  // sum of |m v|: what momentum round-off is relative to
};

template <int D> Totals<D> totals(const Particles<D>& P) {
  double buf[D + 2] = {};
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    if (P.kind[i] != kFluid) continue;  // walls move as prescribed
    buf[0] += 0.5 * P.m[i] * P.v[i].squaredNorm();
    buf[1] += P.m[i] * P.v[i].norm();
    for (int a = 0; a < D; ++a) buf[2 + a] += P.m[i] * P.v[i][a];
  }
  MPI_Allreduce(MPI_IN_PLACE, buf, D + 2, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  Totals<D> t;
  t.kinetic_energy = buf[0];
  t.momentum_scale = buf[1];
  for (int a = 0; a < D; ++a) t.momentum[a] = buf[2 + a];
  return t;
}

template <int D> double fluid_mass(const Particles<D>& P) {
  double m = 0.0;
  for (std::size_t i = 0; i < P.n_owned; ++i)
    if (P.kind[i] == kFluid) m += P.m[i];
  MPI_Allreduce(MPI_IN_PLACE, &m, 1, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  return m;
}

// Run health: stops a run whose state is no longer a number, whose fluid left the box through a
// non-periodic side (walls crossed), or whose kinetic energy exceeds `ke_bound`.
template <int D> void check_health(const Particles<D>& P, const Domain<D>& domain, double ke_bound) {
  int bad[2] = {0, 0};  // NaN, outside
  double ke = 0.0;
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    if (!P.x[i].allFinite() || !P.v[i].allFinite() || !std::isfinite(P.p[i])) bad[0] = 1;
    if (P.kind[i] != kFluid) continue;
    ke += 0.5 * P.m[i] * P.v[i].squaredNorm();
    for (int a = 0; a < D; ++a)
      if (!domain.periodic[a] && (P.x[i][a] < domain.lo[a] || P.x[i][a] > domain.hi[a])) bad[1] = 1;
  }
  MPI_Allreduce(MPI_IN_PLACE, bad, 2, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, &ke, 1, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  if (bad[0]) throw Error("position, velocity or pressure became NaN/Inf: the run blew up; reduce -cfl or -dt");
  if (bad[1]) throw Error("a fluid particle left the domain through a wall: the run is unstable; reduce -cfl or -dt");
  if (ke > ke_bound)
    throw Error("kinetic energy " + std::to_string(ke) + " exceeds 1000 x its reference scale (1/2 M U^2): the run "
                "blew up; reduce -cfl or -dt");
}

// The state a run starts from (after the solver's set-up, or read from a checkpoint) must be finite:
// a NaN there is the input's fault, not the time step's.
template <int D> void check_initial_state(const Particles<D>& P, double t) {
  int bad = 0;
  for (std::size_t i = 0; i < P.n_owned; ++i)
    if (!P.x[i].allFinite() || !P.v[i].allFinite() || !std::isfinite(P.p[i]) || !std::isfinite(P.rho[i])) bad = 1;
  MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
  if (bad)
    throw Error("the initial state (t = " + std::to_string(t) + ") already holds NaN/Inf positions, velocities, densities "
                "or pressures, before any step: the case's start does not fit the solver's options; check them");
}

// Neighbour-count collapse. The fluid particles' mean count of neighbours inside the kernel support
// falling below half its value at the start means the particles scattered (a blow-up under way, or a
// free surface torn apart); in scenes without a free surface, a fluid particle left with fewer than a
// quarter of the smallest count at the start means a void opened beside it (tensile instability).
// Counted on the current lists, which may miss pairs that came within reach since the last rebuild.
template <int D> class NeighbourCountCheck {
 public:
  explicit NeighbourCountCheck(bool free_surface) : free_surface_(free_surface) {}

  void operator()(const Particles<D>& P, const NeighbourList<D>& nl, double support) {
    double sum = 0.0, count = 0.0, fewest = std::numeric_limits<double>::infinity();
    const double rc2 = support * support;
    const std::ptrdiff_t rows = static_cast<std::ptrdiff_t>(std::min(P.n_owned, nl.size()));
    // Threaded: the sums are of whole numbers, exact in any order, so every thread count gives the
    // same figures (a serial pass was 2 % of a one-thread WCSPH step, more of a threaded one).
#pragma omp parallel for schedule(static) reduction(+ : sum, count) reduction(min : fewest)
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
      const std::size_t i = static_cast<std::size_t>(r);
      if (P.kind[i] != kFluid) continue;
      double k = 0.0;
      for (const int* j = nl.begin(i); j != nl.end(i); ++j) k += (P.x[i] - P.x[*j]).squaredNorm() < rc2;
      sum += k, count += 1.0, fewest = std::min(fewest, k);
    }
    double buf[2] = {sum, count};
    MPI_Allreduce(MPI_IN_PLACE, buf, 2, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
    MPI_Allreduce(MPI_IN_PLACE, &fewest, 1, MPI_DOUBLE, MPI_MIN, PETSC_COMM_WORLD);
    if (buf[1] == 0.0) return;
    const double mean = buf[0] / buf[1];
    if (mean0_ < 0) {
      mean0_ = mean, fewest0_ = fewest;
      return;
    }
    std::ostringstream msg;
    if (mean < 0.5 * mean0_)
      msg << "neighbour count collapsed: fluid particles have " << mean << " neighbours on average (" << mean0_
          << " at the start): the particles scattered; reduce -cfl or -dt";
    else if (!free_surface_ && fewest < 0.25 * fewest0_)
      msg << "neighbour count collapsed: a fluid particle has " << fewest << " neighbours (at least " << fewest0_
          << " at the start): a void opened in the fluid (tensile instability); keep shifting on or reduce -cfl";
    if (!msg.str().empty()) throw Error(msg.str());
  }

 private:
  bool free_surface_;
  double mean0_ = -1.0, fewest0_ = 0.0;
};

}  // namespace sph
