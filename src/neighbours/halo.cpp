#include "src/neighbours/halo.hpp"

#include <array>

#include "src/core/error.hpp"

namespace sph {

template <int D> Halo<D>::Halo() = default;

template <int D> Halo<D>::~Halo() {
  if (sf_) PetscSFDestroy(&sf_);
}

template <int D> void Halo<D>::build(Particles<D>& P, const Domain<D>& domain, double width) {
  PetscMPIInt size, rank;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (size > 1)
    throw Error("running on more than one MPI rank is not supported yet (no cross-rank halo); run without mpirun");
  const Vector<D> L = domain.length();
  for (int a = 0; a < D; ++a)
    if (domain.periodic[a] && 2.0 * width >= L[a])
      throw Error("periodic box is too small for the kernel support (needs length > " +
                  std::to_string(2.0 * width) + " along axis " + std::to_string(a) +
                  "); use more particles or a smaller -h_over_dx");

  n_owned_ = P.n_owned;
  shift_.clear();
  owner_rank_.clear();
  std::vector<PetscInt> leaf;
  std::vector<PetscSFNode> root;

  // Every non-zero shift s in {-1,0,1}^D along periodic axes; a particle gets the image x + s*L
  // when it lies within `width` of each face the shift crosses.
  int combos = 1;
  for (int a = 0; a < D; ++a) combos *= 3;
  for (std::size_t i = 0; i < n_owned_; ++i) {
    for (int c = 0; c < combos; ++c) {
      std::array<int, D> s;
      bool any = false, ok = true;
      for (int a = 0, k = c; a < D; ++a, k /= 3) {
        s[a] = k % 3 - 1;
        if (s[a] == 0) continue;
        any = true;
        if (!domain.periodic[a]) ok = false;
        else if (s[a] < 0 && P.x[i][a] < domain.hi[a] - width) ok = false;
        else if (s[a] > 0 && P.x[i][a] >= domain.lo[a] + width) ok = false;
      }
      if (!any || !ok) continue;
      Vector<D> sh;
      for (int a = 0; a < D; ++a) sh[a] = s[a] * L[a];
      leaf.push_back(static_cast<PetscInt>(n_owned_ + shift_.size()));
      root.push_back({rank, static_cast<PetscInt>(i)});
      shift_.push_back(sh);
      owner_rank_.push_back(rank);
    }
  }

  if (sf_) SPH_PETSC(PetscSFDestroy(&sf_));
  SPH_PETSC(PetscSFCreate(PETSC_COMM_WORLD, &sf_));
  SPH_PETSC(PetscSFSetGraph(sf_, static_cast<PetscInt>(n_owned_), static_cast<PetscInt>(leaf.size()),
                            leaf.data(), PETSC_COPY_VALUES, root.data(), PETSC_COPY_VALUES));
  SPH_PETSC(PetscSFSetUp(sf_));

  P.set_ghost_count(shift_.size());
  update_all(P);
}

template <int D> void Halo<D>::update_positions(std::vector<Vector<D>>& x) const {
  update(x);
  for (std::size_t g = 0; g < shift_.size(); ++g) x[n_owned_ + g] += shift_[g];
}

template <int D> void Halo<D>::update_all(Particles<D>& P) const {
  update_positions(P.x);
  update(P.v);
  update(P.m);
  update(P.rho);
  update(P.p);
  update(P.kind);
  update(P.gid);
}

template class Halo<1>;
template class Halo<2>;
template class Halo<3>;

}  // namespace sph
