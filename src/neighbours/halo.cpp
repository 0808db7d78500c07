#include "src/neighbours/halo.hpp"

#include <limits>

#include "src/core/error.hpp"

namespace sph {

template <int D> Halo<D>::Halo() = default;

template <int D> Halo<D>::~Halo() {
  if (sf_) PetscSFDestroy(&sf_);
}

namespace {

// Every rank's bounding box of owned particles, grown by the width: a particle (or a periodic image
// of it) inside rank r's grown box may be within `width` of one of r's particles, so r gets a ghost
// of it. A superset of what is needed; the neighbour lists keep only pairs within reach. Rank r's box
// is [boxes[2 D r + a], boxes[2 D r + D + a]] along axis a.
template <int D> std::vector<double> grown_boxes(const Particles<D>& P, std::size_t n_owned, double width, int size) {
  std::vector<double> boxes(2 * D * size);
  Vector<D> lo = Vector<D>::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (std::size_t i = 0; i < n_owned; ++i) lo = lo.cwiseMin(P.x[i]), hi = hi.cwiseMax(P.x[i]);
  std::vector<double> mine(2 * D);
  for (int a = 0; a < D; ++a) mine[a] = lo[a] - width, mine[D + a] = hi[a] + width;
  MPI_Allgather(mine.data(), 2 * D, MPI_DOUBLE, boxes.data(), 2 * D, MPI_DOUBLE, PETSC_COMM_WORLD);
  return boxes;
}

// Periodic shifts s in {-1,0,1}^D, numbered c = sum_a (s_a + 1) 3^a; those the domain's periodicity
// allows (non-zero only along periodic axes).
template <int D> struct Shifts {
  Vector<D> L;
  std::vector<int> allowed;
  int zero = 0;  // the code of no shift
  explicit Shifts(const Domain<D>& domain) : L(domain.length()) {
    int combos = 1;
    for (int a = 0; a < D; ++a) combos *= 3;
    for (int c = 0; c < combos; ++c) {
      bool ok = true;
      for (int a = 0, k = c; a < D; ++a, k /= 3)
        if (k % 3 != 1 && !domain.periodic[a]) ok = false;
      if (ok) allowed.push_back(c);
    }
    zero = (combos - 1) / 2;
  }
  Vector<D> of(int c) const {
    Vector<D> sh;
    for (int a = 0; a < D; ++a, c /= 3) sh[a] = (c % 3 - 1) * L[a];
    return sh;
  }
};

// What every rank receives: (source index, shift code) pairs, in order of source rank, with the
// count and offset (in ints) from each rank.
struct GhostRequests {
  std::vector<int> recv, count, displ;
};

GhostRequests exchange_requests(const std::vector<std::vector<int>>& outgoing, int size) {
  std::vector<int> send_count(size), send_displ(size, 0);
  GhostRequests in{{}, std::vector<int>(size), std::vector<int>(size, 0)};
  for (int r = 0; r < size; ++r) send_count[r] = static_cast<int>(outgoing[r].size());
  MPI_Alltoall(send_count.data(), 1, MPI_INT, in.count.data(), 1, MPI_INT, PETSC_COMM_WORLD);
  for (int r = 1; r < size; ++r) {
    send_displ[r] = send_displ[r - 1] + send_count[r - 1];
    in.displ[r] = in.displ[r - 1] + in.count[r - 1];
  }
  std::vector<int> send;
  in.recv.resize(static_cast<std::size_t>(in.displ[size - 1]) + in.count[size - 1]);
  for (const auto& o : outgoing) send.insert(send.end(), o.begin(), o.end());
  MPI_Alltoallv(send.data(), send_count.data(), send_displ.data(), MPI_INT, in.recv.data(), in.count.data(),
                in.displ.data(), MPI_INT, PETSC_COMM_WORLD);
  return in;
}

}  // namespace

template <int D> void Halo<D>::build(Particles<D>& P, const Domain<D>& domain, double width) {
  PetscMPIInt size, rank;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  const Vector<D> L = domain.length();
  for (int a = 0; a < D; ++a)
    if (domain.periodic[a] && 2.0 * width >= L[a])
      throw Error("periodic box is too small for the kernel support (needs length > " + std::to_string(2.0 * width) +
                  " along axis " + std::to_string(a) + "); use more particles or a smaller -h_over_dx");
  n_owned_ = P.n_owned;
  const std::vector<double> boxes = grown_boxes(P, n_owned_, width, size);
  auto inside = [&](int r, const Vector<D>& y) {
    for (int a = 0; a < D; ++a)
      if (y[a] < boxes[2 * D * r + a] || y[a] > boxes[2 * D * r + D + a]) return false;
    return true;
  };
  const Shifts<D> shifts(domain);
  // (source index, shift code) pairs for each destination rank.
  std::vector<std::vector<int>> outgoing(size);
  for (std::size_t i = 0; i < n_owned_; ++i)
    for (int c : shifts.allowed) {
      const Vector<D> y = P.x[i] + shifts.of(c);
      for (int r = 0; r < size; ++r) {
        if (r == rank && c == shifts.zero) continue;  // the particle itself
        if (inside(r, y)) outgoing[r].push_back(static_cast<int>(i)), outgoing[r].push_back(c);
      }
    }
  const GhostRequests in = exchange_requests(outgoing, size);

  // Ghosts in order of source rank, then of the source's order.
  const std::size_t n_ghost = in.recv.size() / 2;
  shift_.resize(n_ghost);
  owner_rank_.resize(n_ghost);
  std::vector<PetscInt> leaf(n_ghost);
  std::vector<PetscSFNode> root(n_ghost);
  for (int r = 0, g = 0; r < size; ++r)
    for (int k = in.displ[r]; k < in.displ[r] + in.count[r]; k += 2, ++g) {
      leaf[g] = static_cast<PetscInt>(n_owned_ + g);
      root[g] = {r, static_cast<PetscInt>(in.recv[k])};
      shift_[g] = shifts.of(in.recv[k + 1]);
      owner_rank_[g] = r;
    }
  if (sf_) SPH_PETSC(PetscSFDestroy(&sf_));
  SPH_PETSC(PetscSFCreate(PETSC_COMM_WORLD, &sf_));
  SPH_PETSC(PetscSFSetGraph(sf_, static_cast<PetscInt>(n_owned_), static_cast<PetscInt>(n_ghost), leaf.data(),
                            PETSC_COPY_VALUES, root.data(), PETSC_COPY_VALUES));
  SPH_PETSC(PetscSFSetUp(sf_));
  P.set_ghost_count(n_ghost);
  particles_ = &P;
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
  update(P.id);
  // And the registry's: a new ghost layer holds rows of other particles, or zeros, until they are
  // copied.
  P.fields.for_each_column([this](auto& column) { update(column); });
  P.stale = StaleGhosts<D>{};
}

template <int D> void Halo<D>::refresh_stale() const {
  if (!particles_ || !particles_->stale.any()) return;
  Particles<D>& P = *particles_;
  StaleGhosts<D>& s = P.stale;
  if (s.v) update(P.v);
  if (s.m) update(P.m);
  if (s.rho) update(P.rho);
  if (s.p) update(P.p);
  for (std::vector<double>* f : s.scalars) update(*f);
  for (std::vector<Vector<D>>* f : s.vectors) update(*f);
  s = StaleGhosts<D>();
}

template class Halo<1>;
template class Halo<2>;
template class Halo<3>;

}  // namespace sph
