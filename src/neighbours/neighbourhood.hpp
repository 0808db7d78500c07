#pragma once
// Ghost layer + neighbour lists kept valid as particles move (a Verlet list with a skin).
// Lists are built with radius (support + skin); between rebuilds the pair loops evaluate the kernel
// at current positions, so a list stays exact while no particle has moved more than skin/2.
#include "src/neighbours/halo.hpp"
#include "src/neighbours/neighbour_list.hpp"

namespace sph {

template <int D> class Neighbourhood {
 public:
  Neighbourhood(const Domain<D>& domain, double support_radius, double skin)
      : domain_(domain), support_(support_radius), skin_(skin), skin_fraction_(skin / support_radius) {}

  // Call after owned positions changed. Rebuilds (wrapping owned particles back into a periodic box,
  // re-making ghosts and lists) when needed or forced; otherwise refreshes ghost positions and
  // velocities. Returns true when it rebuilt; the ghost count may then have changed. Thin plates'
  // screens are applied at every call, at the current positions.
  bool update(Particles<D>& P, bool force = false);

  // What an update that does not rebuild does: the ghosts to the owned particles' positions and
  // velocities, and the plates' screens at the current positions (a restart's lists, built at the
  // writing run's places, are brought to the particles' places so).
  void refresh(Particles<D>& P);

  const NeighbourList<D>& list() const { return list_; }
  const Halo<D>& halo() const { return halo_; }
  const Domain<D>& domain() const { return domain_; }
  double support_radius() const { return support_; }
  // Schemes with variable smoothing lengths widen or narrow the search; the skin keeps its fraction of
  // the support, and the next update() rebuilds.
  void set_support_radius(double support) { support_ = support, skin_ = skin_fraction_ * support, x_at_build_.clear(); }
  long rebuilds() const { return rebuilds_; }
  // The owned positions the lists were last built at (wrapped into a periodic box), in storage order:
  // what the next update() measures the displacements from. Empty until the first build and after
  // set_support_radius.
  const std::vector<Vector<D>>& x_at_build() const { return x_at_build_; }

 private:
  Domain<D> domain_;
  double support_, skin_, skin_fraction_;
  Halo<D> halo_;
  // With thin plates: which pairs a plate separates depends on where the particles are now. Decided
  // at the rebuild and kept for the list's life, it made the run depend on when the list was last
  // rebuilt: the list as built is kept, and screened again at every update
  // (docs/verification/free_surface.md, "Answers that the rebuild schedule moved").
  void screen(const Particles<D>& P);
  NeighbourList<D> list_, unscreened_;
  std::vector<Vector<D>> x_at_build_;
  long rebuilds_ = 0;
};

}  // namespace sph
