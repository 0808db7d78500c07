#pragma once
// Ghost (halo) particles: copies of particles within a given width of this rank's particles that
// live on another rank or across a periodic face (or both). Each ghost knows its
// source (owner rank + owner's local index) and a position shift (the periodic offset). Field
// refreshes go through a PetscSF, so one rank is simply the case where every source is local.
#include <petscsf.h>

#include <type_traits>
#include <vector>

#include "src/core/domain.hpp"
#include "src/core/error.hpp"
#include "src/particles/particles.hpp"

namespace sph {

template <int D> class Halo {
 public:
  Halo();
  ~Halo();
  Halo(const Halo&) = delete;
  Halo& operator=(const Halo&) = delete;

  // Rebuilds the ghost layer for owned particles at their current positions and fills every field
  // of `P` in the ghost slots.
  void build(Particles<D>& P, const Domain<D>& domain, double width);

  // Copy owned values into the ghost slots (the vector is resized to owned + ghost first).
  // T is a scalar (double, int, GlobalIndex) or a fixed-size Eigen vector/matrix of doubles.
  template <class T> void update(std::vector<T>& field) const;
  // Positions: a copy plus the ghost's periodic shift.
  void update_positions(std::vector<Vector<D>>& x) const;
  // Every field the Particles struct holds, the registry's columns included; the stale marks cleared.
  void update_all(Particles<D>& P) const;
  // The columns of the particles this halo serves (the last built or refreshed for) that were marked
  // written (Particles::written): refreshed, and the marks cleared. Pair loops and ghost checks call it.
  void refresh_stale() const;
  void serve(Particles<D>& P) { particles_ = &P; }

  std::size_t n_owned() const { return n_owned_; }
  std::size_t n_ghost() const { return shift_.size(); }
  // Rank that owns the source of ghost g (0-based among ghosts).
  PetscMPIInt owner_rank(std::size_t g) const { return owner_rank_[g]; }

 private:
  std::size_t n_owned_ = 0;
  std::vector<Vector<D>> shift_;
  std::vector<PetscMPIInt> owner_rank_;
  PetscSF sf_ = nullptr;
  Particles<D>* particles_ = nullptr;
};

template <int D> template <class T> void Halo<D>::update(std::vector<T>& field) const {
  field.resize(n_owned_ + shift_.size());
  if (!sf_) return;
  MPI_Datatype type;
  bool derived = false;
  if constexpr (std::is_same_v<T, double>) type = MPI_DOUBLE;
  else if constexpr (std::is_same_v<T, int>) type = MPI_INT;
  else if constexpr (std::is_same_v<T, long long>) type = MPI_LONG_LONG;
  else {
    static_assert(sizeof(T) % sizeof(double) == 0, "halo fields are scalars or arrays of doubles");
    MPI_Type_contiguous(static_cast<int>(sizeof(T) / sizeof(double)), MPI_DOUBLE, &type);
    MPI_Type_commit(&type);
    derived = true;
  }
  // Roots are the owned entries and leaves the ghost entries of the same array.
  PetscErrorCode ierr = PetscSFBcastBegin(sf_, type, field.data(), field.data(), MPI_REPLACE);
  if (!ierr) ierr = PetscSFBcastEnd(sf_, type, field.data(), field.data(), MPI_REPLACE);
  if (derived) MPI_Type_free(&type);
  check_petsc(ierr, "PetscSFBcast");
}

}  // namespace sph
