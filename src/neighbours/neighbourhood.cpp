#include "src/neighbours/neighbourhood.hpp"

#include <mpi.h>

#include <cmath>
#include <limits>

#include "src/core/log_events.hpp"

namespace sph {

template <int D> bool Neighbourhood<D>::update(Particles<D>& P, bool force) {
  const LogEventScope log_update(LogEvent::NeighbourUpdate);
  // Every rank takes the same decision (the rebuild is collective).
  double max_disp2 = force || x_at_build_.size() != P.n_owned ? std::numeric_limits<double>::infinity() : 0.0;
  for (std::size_t i = 0; i < P.n_owned && x_at_build_.size() == P.n_owned; ++i)
    max_disp2 = std::max(max_disp2, (P.x[i] - x_at_build_[i]).squaredNorm());
  MPI_Allreduce(MPI_IN_PLACE, &max_disp2, 1, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
  // Two particles each moving skin/2 towards each other is the worst case the skin covers.
  const bool rebuild = 2.0 * std::sqrt(max_disp2) >= skin_;
  if (!rebuild) {
    refresh(P);
    return false;
  }
  const LogEventScope log_rebuild(LogEvent::NeighbourRebuild);
  for (std::size_t i = 0; i < P.n_owned; ++i) P.x[i] = domain_.wrap(P.x[i]);
  const double radius = support_ + skin_;
  halo_.build(P, domain_, radius);
  list_.build(P.x, P.n_owned, radius);
  list_.set_halo(&halo_);
  if (domain_.screens && domain_.screens->any()) unscreened_ = list_, screen(P);
  x_at_build_.assign(P.x.begin(), P.x.begin() + P.n_owned);
  ++rebuilds_;
  return true;
}

template <int D> void Neighbourhood<D>::refresh(Particles<D>& P) {
  halo_.serve(P);
  halo_.update_positions(P.x);
  halo_.update(P.v);
  P.stale.v = false;
  if (domain_.screens && domain_.screens->any()) screen(P);
}

template <int D> void Neighbourhood<D>::screen(const Particles<D>& P) {
  const Screens<D>& screens = *domain_.screens;
  list_ = unscreened_;
  list_.filter([&](std::size_t i, int j) { return screens.see(P.x[i], P.id[i], P.x[j], P.id[j]); });
}

template class Neighbourhood<1>;
template class Neighbourhood<2>;
template class Neighbourhood<3>;

}  // namespace sph
