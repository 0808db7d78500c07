#pragma once
// Domain decomposition by a space-filling curve: owned particles are ordered along a Morton (Z-order)
// curve through the bounding box of all particles, and rank r receives the r-th of `size` equal
// contiguous pieces of that order. Neighbours along the curve are mostly neighbours in space, so each
// rank's particles form a compact region (few ghosts) and, on any rank count, memory order follows
// space (cache locality of the pair loops).
#include <cstdint>
#include <vector>

#include "src/core/domain.hpp"
#include "src/particles/particles.hpp"

namespace sph {

// Morton key of x in the box [lo, hi] (bits interleaved, 64/D bits per axis).
template <int D> std::uint64_t morton_key(const Vector<D>& x, const Vector<D>& lo, const Vector<D>& hi);

// Wraps owned particles into the periodic box, re-orders (and on several ranks migrates) them along
// the curve with their carried fields (FieldUse kCarried), renumbers global indices, and drops the
// ghosts (the caller rebuilds its neighbourhood).
// Deterministic: the result depends only on the set of particles (ties broken by permanent id), not on
// where they were.
// Returns the load imbalance afterwards: max owned count / mean owned count.
template <int D> double partition_along_curve(Particles<D>& P, const Domain<D>& domain);

// Puts every owned particle back on the rank and at the place it had in an earlier partition of the
// same particles (a checkpoint's record): place[i] is particle i's global index there, owned[r] the
// count rank r held (one entry per rank). Moves the carried fields with them, as the partition does,
// renumbers global indices and drops the ghosts; positions are left as they are (not wrapped).
// Throws sph::Error when the record does not fit the particles. Returns the load imbalance.
template <int D>
double restore_order(Particles<D>& P, const std::vector<GlobalIndex>& place, const std::vector<GlobalIndex>& owned);

}  // namespace sph
