#pragma once
// Whole-system figures and run-health checks, reduced over all ranks.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <utility>

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

// The owned fluid particle with the smallest label among those `bad` picks (over all ranks): its label
// and position, for messages that say where something went wrong; label -1 when there is none.
template <int D> struct NamedParticle {
  long long label = -1;
  Vector<D> x = Vector<D>::Zero();
  std::string where() const {
    std::ostringstream s;
    s << "fluid particle " << label << " near (";
    for (int a = 0; a < D; ++a) s << (a ? ", " : "") << x[a];
    s << ")";
    return s.str();
  }
};

template <int D, class Pick> NamedParticle<D> first_particle(const Particles<D>& P, Pick&& bad) {
  long long label = std::numeric_limits<long long>::max();
  std::size_t local = P.n_owned;
  for (std::size_t i = 0; i < P.n_owned; ++i)
    if (P.kind[i] == kFluid && bad(i) && P.id[i] < label) label = P.id[i], local = i;
  long long global = label;
  MPI_Allreduce(MPI_IN_PLACE, &global, 1, MPI_LONG_LONG, MPI_MIN, PETSC_COMM_WORLD);
  NamedParticle<D> out;
  if (global == std::numeric_limits<long long>::max()) return out;
  out.label = global;
  if (local < P.n_owned && label == global) out.x = P.x[local];
  MPI_Allreduce(MPI_IN_PLACE, out.x.data(), D, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  return out;
}

// The fluid particles closer than half a spacing to a wall particle: inside a wall, since a wall's face
// lies half a spacing from its first layer. Counted on the current lists (pairs that came within reach
// since the last rebuild may be missed). All ranks.
template <int D> long fluid_in_walls(const Particles<D>& P, const NeighbourList<D>& nl, double dx) {
  const double r2 = 0.25 * dx * dx;
  long count = 0;
  const std::ptrdiff_t rows = static_cast<std::ptrdiff_t>(std::min(P.n_owned, nl.size()));
#pragma omp parallel for schedule(static) reduction(+ : count)
  for (std::ptrdiff_t r = 0; r < rows; ++r) {
    const std::size_t i = static_cast<std::size_t>(r);
    if (P.kind[i] != kFluid) continue;
    bool inside = false;
    for (const int* j = nl.begin(i); j != nl.end(i) && !inside; ++j)
      inside = P.kind[*j] == kWall && (P.x[i] - P.x[*j]).squaredNorm() < r2;
    count += inside;
  }
  MPI_Allreduce(MPI_IN_PLACE, &count, 1, MPI_LONG, MPI_SUM, PETSC_COMM_WORLD);
  return count;
}

// The share of fluid particles where `flag` (one value per owned particle) is nonzero. All ranks.
template <int D> double fluid_share(const Particles<D>& P, const std::vector<double>& flag) {
  double sums[2] = {0.0, 0.0};
  for (std::size_t i = 0; i < P.n_owned; ++i)
    if (P.kind[i] == kFluid) sums[0] += flag[i] != 0.0, sums[1] += 1.0;
  MPI_Allreduce(MPI_IN_PLACE, sums, 2, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  return sums[1] > 0.0 ? sums[0] / sums[1] : 0.0;
}

// A blow-up's advice. A smaller step helps only where the step caused it, and only from a state not yet
// damaged, which the last checkpoint before a blow-up often is not (docs/user-guide.md, "Failure messages").
// `courant_option` is the scheme's Courant number (-cfl or -acoustic_cfl, Solver::courant_option).
inline std::string blow_up_advice(const std::string& courant_option) {
  return "if the time step is the cause, a smaller " + courant_option +
         " or -dt from the start (or from a checkpoint well before, -checkpoints_kept) runs past this time; if it "
         "fails as soon, look at the particle named";
}

// Run health: stops a run whose state is no longer a number, whose fluid left the box through a
// non-periodic side (walls crossed, or the open top of a scene), or whose kinetic energy exceeds
// `ke_bound`. The message names the first such particle and where it is.
// `escapes_removed`: fluid that left over an open side has been taken out already (-box_exit auto), so
// what is outside went through a wall.
template <int D> void check_health(const Particles<D>& P, const Domain<D>& domain, double ke_bound,
                                   const std::string& courant_option, bool escapes_removed = false) {
  auto not_finite = [&](std::size_t i) { return !P.x[i].allFinite() || !P.v[i].allFinite() || !std::isfinite(P.p[i]); };
  auto outside = [&](std::size_t i) { return domain.outside(P.x[i]); };
  int bad[2] = {0, 0};  // NaN, outside
  double ke = 0.0;
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    if (not_finite(i)) bad[0] = 1;
    if (P.kind[i] != kFluid) continue;
    ke += 0.5 * P.m[i] * P.v[i].squaredNorm();
    if (outside(i)) bad[1] = 1;
  }
  MPI_Allreduce(MPI_IN_PLACE, bad, 2, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, &ke, 1, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  if (bad[0]) {
    const NamedParticle<D> p = first_particle(P, not_finite);
    throw Error("position, velocity or pressure became NaN/Inf" +
                (p.label >= 0 ? " (" + p.where() + " first)" : std::string()) + ": the run blew up; " +
                blow_up_advice(courant_option));
  }
  if (bad[1]) {
    const NamedParticle<D> p = first_particle(P, outside);
    std::ostringstream msg;
    msg << p.where() << " left the box [";
    for (int a = 0; a < D; ++a) msg << (a ? ", " : "") << domain.lo[a] << ", " << domain.hi[a];
    if (escapes_removed)
      msg << "] through a wall (where it crossed the box's side, a wall's particles lie): the walls let it through "
             "(see fluid_in_walls in timeseries.csv); -box_exit remove would take it out of the run instead";
    else
      msg << "]: it went through a wall or over the box's open top; if the fluid may fly that high, enlarge the "
             "scene's box or take such fluid out of the run (-box_exit auto or remove), else the walls let it "
             "through (see fluid_in_walls in timeseries.csv)";
    throw Error(msg.str());
  }
  if (ke > ke_bound) {
    // The fastest particle: where the blow-up started, most often.
    double fastest = 0.0;
    for (std::size_t i = 0; i < P.n_owned; ++i)
      if (P.kind[i] == kFluid) fastest = std::max(fastest, P.v[i].norm());
    MPI_Allreduce(MPI_IN_PLACE, &fastest, 1, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
    const NamedParticle<D> p = first_particle(P, [&](std::size_t i) { return P.v[i].norm() == fastest; });
    std::ostringstream msg;
    msg << "kinetic energy " << ke << " exceeds 1000 x its reference scale (1/2 M U^2), " << p.where()
        << " the fastest at speed " << fastest << ": the run blew up; " << blow_up_advice(courant_option);
    throw Error(msg.str());
  }
}

// The state a run starts from (after the solver's set-up, or read from a checkpoint) must be finite:
// a NaN there is the input's fault, not the time step's.
template <int D> void check_initial_state(const Particles<D>& P, double t) {
  int bad = 0;
  for (std::size_t i = 0; i < P.n_owned; ++i)
    if (!P.x[i].allFinite() || !P.v[i].allFinite() || !std::isfinite(P.p[i]) || !std::isfinite(P.rho[i])) bad = 1;
  MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
  if (bad)
    throw Error("the initial state (t = " + std::to_string(t) +
                ") already holds NaN/Inf positions, velocities, densities "
                "or pressures, before any step: the case's start does not fit the solver's options; check them");
}

// Neighbour-count collapse. The fluid particles' mean count of neighbours inside the kernel support
// falling below half its value at the start means the particles scattered (a blow-up under way, or a
// free surface torn apart); in scenes without a free surface, a fluid particle left with fewer than a
// quarter of the smallest count at the start means a void opened beside it (tensile instability).
// Counted on the current lists, which may miss pairs that came within reach since the last rebuild.
template <int D> class NeighbourCountCheck {
 public:
  NeighbourCountCheck(bool free_surface, std::string courant_option)
      : free_surface_(free_surface), courant_option_(std::move(courant_option)) {}

  void operator()(const Particles<D>& P, const NeighbourList<D>& nl, double support) {
    double sum = 0.0, count = 0.0, fewest = std::numeric_limits<double>::infinity();
    const double rc2 = support * support;
    const std::ptrdiff_t rows = static_cast<std::ptrdiff_t>(std::min(P.n_owned, nl.size()));
    // Threaded: the sums are of whole numbers, exact in any order, so every thread count gives the
    // same figures, and a serial pass costs a visible share of a step (docs/performance.md, "Design
    // measurements").
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
    // In a splash the fluid thins into sheets and drops narrower than the kernel support: a finer
    // -nx resolves them, a smaller step does not (docs/user-guide.md, "Failure messages").
    if (mean < 0.5 * mean0_ && free_surface_)
      msg << "neighbour count collapsed: fluid particles have " << mean << " neighbours on average (" << mean0_
          << " at the start): the fluid broke into sheets and drops thinner than the kernel support, or blew up "
             "(see kinetic_energy in timeseries.csv); a finer -nx resolves a splash's sheets, a smaller "
          << courant_option_ << " does not";
    else if (mean < 0.5 * mean0_)
      msg << "neighbour count collapsed: fluid particles have " << mean << " neighbours on average (" << mean0_
          << " at the start): the particles scattered; reduce " << courant_option_ << " or -dt";
    else if (!free_surface_ && fewest < 0.25 * fewest0_)
      msg << "neighbour count collapsed: a fluid particle has " << fewest << " neighbours (at least " << fewest0_
          << " at the start): a void opened in the fluid (tensile instability); keep shifting on or reduce "
          << courant_option_;
    if (!msg.str().empty()) throw Error(msg.str());
  }

 private:
  bool free_surface_;
  std::string courant_option_;
  double mean0_ = -1.0, fewest0_ = 0.0;
};

}  // namespace sph
