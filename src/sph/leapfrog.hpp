#pragma once
// The time step of the explicit schemes (WCSPH and the compressible solver): kick-drift-kick
// (velocity Verlet), one rate evaluation per step. With the rates a^n, r^n of the previous evaluation,
//   v^{n+1/2} = v^n + dt/2 a^n,   f^{n+1/2} = f^n + dt/2 r^n          (kick)
//   x^{n+1}   = x^n + dt v^{n+1/2}          (particles that move)     (drift)
//   v, f predicted to t^{n+1} as v^{n+1/2} + dt/2 a^n, f^{n+1/2} + dt/2 r^n, for the velocity- and
//   state-dependent terms of the rate evaluation a^{n+1}, r^{n+1} = rates()
//   v^{n+1}   = v^{n+1/2} + dt/2 a^{n+1},  f^{n+1} = f^{n+1/2} + dt/2 r^{n+1}   (kick)
// Second order for rates that depend on positions only; the predicted velocity keeps velocity-dependent
// terms (viscosity) at first order in their lag. Particles with zero rates keep their values.
#include <algorithm>
#include <cstddef>
#include <limits>
#include <vector>

#include "src/core/types.hpp"

namespace sph {

// A per-particle scalar integrated with its rate (density, thermal energy, viscosity switch); bounds,
// where given, hold its predicted and final values (not the half-step one).
struct LeapfrogScalar {
  std::vector<double>* value;
  const std::vector<double>* rate;  // read again after rates(): the rate evaluation updates it in place
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
};

// Sees nothing of the kicks (kick_seen's default).
struct NoKickObserver {
  template <class V, class F> void operator()(const V&, const F&) const {}
};

// One step for the first n particles. moves(i): whether particle i drifts (walls keep their place);
// rates(): refreshes acc and the scalars' rates at the drifted positions and predicted values.
// before_kick(v, f): called before each of the two kicks with the velocities and scalar values it
// starts from, while acc and the rates are the ones it applies (the energy budget's hook).
template <int D, class MovesFn, class RatesFn, class KickFn = NoKickObserver>
void leapfrog_step(double dt, std::size_t n, std::vector<Vector<D>>& x, std::vector<Vector<D>>& v,
                   const std::vector<Vector<D>>& acc, const std::vector<LeapfrogScalar>& scalars, MovesFn&& moves,
                   RatesFn&& rates, KickFn&& before_kick = KickFn()) {
  const double half_dt = 0.5 * dt;
  std::vector<Vector<D>> v_half(n);
  std::vector<std::vector<double>> f_half(scalars.size(), std::vector<double>(n));
  std::vector<const std::vector<double>*> f_from;
  for (const LeapfrogScalar& s : scalars) f_from.push_back(s.value);
  before_kick(v, f_from);
  for (std::size_t i = 0; i < n; ++i) {
    v_half[i] = v[i] + half_dt * acc[i];
    if (moves(i)) x[i] += dt * v_half[i];
    v[i] = v_half[i] + half_dt * acc[i];
  }
  for (std::size_t k = 0; k < scalars.size(); ++k) {
    const LeapfrogScalar& s = scalars[k];
    for (std::size_t i = 0; i < n; ++i) {
      f_half[k][i] = (*s.value)[i] + half_dt * (*s.rate)[i];
      (*s.value)[i] = std::clamp(f_half[k][i] + half_dt * (*s.rate)[i], s.lo, s.hi);
    }
  }
  rates();
  for (std::size_t k = 0; k < scalars.size(); ++k) f_from[k] = &f_half[k];
  before_kick(v_half, f_from);
  for (std::size_t i = 0; i < n; ++i) v[i] = v_half[i] + half_dt * acc[i];
  for (std::size_t k = 0; k < scalars.size(); ++k) {
    const LeapfrogScalar& s = scalars[k];
    for (std::size_t i = 0; i < n; ++i) (*s.value)[i] = std::clamp(f_half[k][i] + half_dt * (*s.rate)[i], s.lo, s.hi);
  }
}

}  // namespace sph
