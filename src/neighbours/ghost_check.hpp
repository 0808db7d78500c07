#pragma once
// Ghost freshness, checked. A pair loop reads its neighbours' values in the ghost slots: copies that
// the halo made when the owners' values were last refreshed. A copy that missed a write is read
// without a sign, and only across a periodic face or between ranks. With the checks on
// (-check_ghosts, and always in a debug build) every pair loop compares the ghosts of the particles'
// own fields, and each operator those of the fields it is handed, with a fresh copy, and stops at
// the first stale one (docs/developer.md, "Ghosts").
#include <mpi.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "src/neighbours/halo.hpp"
#include "src/neighbours/neighbour_list.hpp"

namespace sph {

// Whether the checks run: -check_ghosts sets it; a debug build starts with it on.
inline bool& ghost_checks() {
#ifdef NDEBUG
  static bool on = false;
#else
  static bool on = true;
#endif
  return on;
}

// Where a check was called from. As a default argument, CallSite() is the caller's file and line.
struct CallSite {
  const char* file;
  int line;
  CallSite(const char* f = __builtin_FILE(), int l = __builtin_LINE()) : file(f), line(l) {}
};

namespace detail {
// The first stale ghost of `fresh` against `f` on any rank (every rank takes part), or -1.
template <class T> long first_stale(const std::vector<T>& fresh, const std::vector<T>& f, std::size_t n_owned) {
  long stale = -1;
  if (f.size() < fresh.size()) stale = static_cast<long>(f.size() > n_owned ? f.size() - n_owned : 0);
  for (std::size_t k = n_owned; k < fresh.size() && stale < 0; ++k)
    if (std::memcmp(&fresh[k], &f[k], sizeof(T)) != 0) stale = static_cast<long>(k - n_owned);
  MPI_Allreduce(MPI_IN_PLACE, &stale, 1, MPI_LONG, MPI_MAX, PETSC_COMM_WORLD);
  return stale;
}

inline void throw_if_stale(long stale, const char* field, CallSite at) {
  if (stale < 0) return;
  throw std::logic_error(std::string("the ghost copies of ") + field + " read by the pair loop at " + at.file + ":" +
                         std::to_string(at.line) + " are stale (ghost " + std::to_string(stale) +
                         "): a value written on owned particles was not refreshed before the loop");
}

// The comparisons, kept out of line: the pair loops that call the checks stay as lean as without them.
template <int D, class T> [[gnu::noinline, gnu::cold]] void compare_ghosts(const Halo<D>& halo, const std::vector<T>& f,
                                                                           const char* field, CallSite at) {
  std::vector<T> fresh(f.begin(), f.begin() + std::min(f.size(), halo.n_owned()));
  halo.update(fresh);
  throw_if_stale(first_stale(fresh, f, halo.n_owned()), field, at);
}

template <int D>
[[gnu::noinline, gnu::cold]] void compare_position_ghosts(const Halo<D>& halo, const Particles<D>& P, CallSite at) {
  std::vector<Vector<D>> x(P.x.begin(), P.x.begin() + std::min(P.x.size(), halo.n_owned()));
  halo.update_positions(x);
  throw_if_stale(first_stale(x, P.x, halo.n_owned()), "x", at);
}

template <int D>
[[gnu::noinline, gnu::cold]] void compare_particle_ghosts(const Halo<D>& halo, const Particles<D>& P, CallSite at) {
  compare_position_ghosts(halo, P, at);
  compare_ghosts(halo, P.v, "v", at);
  compare_ghosts(halo, P.m, "m", at);
  compare_ghosts(halo, P.rho, "rho", at);
  compare_ghosts(halo, P.p, "p", at);
  compare_ghosts(halo, P.kind, "kind", at);
}
}  // namespace detail

// A list is a NeighbourList or any other list whose halo() names the halo its ghost indices refer to.

// Throws std::logic_error when f's ghost slots differ, bit for bit, from their owners' values (after
// the columns marked written are refreshed: a marked column is fresh when read).
template <class List, class T>
void check_ghosts(const List& nl, const std::vector<T>& f, const char* field, CallSite at = CallSite()) {
  if (nl.halo()) nl.halo()->refresh_stale();
  if (ghost_checks() && nl.halo()) detail::compare_ghosts(*nl.halo(), f, field, at);
}

// The ghosts' positions, with their periodic shifts.
template <int D, class List>
void check_position_ghosts(const Particles<D>& P, const List& nl, CallSite at = CallSite()) {
  if (ghost_checks() && nl.halo()) detail::compare_position_ghosts(*nl.halo(), P, at);
}

// Every pair loop starts here: the columns marked written are refreshed (Particles::written), then the
// particles' own fields, which any pair loop may read, are checked (positions with the ghosts' periodic
// shifts).
template <int D, class List> void check_particle_ghosts(const Particles<D>& P, const List& nl, CallSite at) {
  if (nl.halo()) nl.halo()->refresh_stale();
  if (ghost_checks() && nl.halo()) detail::compare_particle_ghosts(*nl.halo(), P, at);
}

}  // namespace sph
