#include "src/neighbours/partition.hpp"

#include <mpi.h>
#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "src/core/error.hpp"
#include "src/particles/global_indices.hpp"

namespace sph {

namespace {

// Bits per axis: keys stay below 2^63, so 2^63 bounds every key in the splitter search.
template <int D> constexpr int kBits = 63 / D;

// Spreads the low kBits<D> bits of v so that D-1 zero bits separate consecutive ones.
template <int D> std::uint64_t spread_bits(std::uint64_t v) {
  if constexpr (D == 1) return v;
  std::uint64_t r = 0;
  for (int b = 0; b < kBits<D>; ++b) r |= ((v >> b) & 1ull) << (b * D);
  return r;
}

struct Keyed {
  std::uint64_t key;
  GlobalIndex id;
  std::size_t slot;  // where the particle's data sits in the local buffer
  bool operator<(const Keyed& o) const { return key != o.key ? key < o.key : id < o.id; }
};

// Moves every owned particle i, with its carried fields, to rank dest[i], where each rank orders the
// particles it receives by (key[i], permanent id): one all-to-all and a local sort. Renumbers global
// indices and drops the ghosts. Returns the load imbalance: max owned count / mean owned count.
template <int D> double migrate(Particles<D>& P, const std::vector<int>& dest, const std::vector<std::uint64_t>& key) {
  PetscMPIInt size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  const std::size_t n = P.n_owned;
  std::vector<Keyed> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = {key[i], P.id[i], i};
  std::sort(order.begin(), order.end(), [&](const Keyed& a, const Keyed& b) {
    return dest[a.slot] != dest[b.slot] ? dest[a.slot] < dest[b.slot] : a < b;
  });

  // Pack every particle, grouped by destination, into one row of doubles per particle; the key goes
  // as two 32-bit halves (exact in doubles).
  std::vector<ParticleField> fields = P.fields.with(kCarried, n);
  int stride = 2 * D + 7;
  for (const ParticleField& f : fields) stride += f.components;
  std::vector<double> send(n * stride);
  std::vector<int> send_count(size, 0);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = order[k].slot;
    double* row = &send[k * stride];
    for (int a = 0; a < D; ++a) *row++ = P.x[i][a];
    for (int a = 0; a < D; ++a) *row++ = P.v[i][a];
    *row++ = P.m[i], *row++ = P.rho[i], *row++ = P.p[i];
    *row++ = P.kind[i], *row++ = static_cast<double>(P.id[i]);  // exact below 2^53
    *row++ = static_cast<double>(key[i] >> 32), *row++ = static_cast<double>(key[i] & 0xffffffffu);
    for (const ParticleField& f : fields)
      for (int c = 0; c < f.components; ++c) *row++ = f.data[i * f.components + c];
    send_count[dest[i]] += stride;
  }

  std::vector<int> recv_count(size), send_displ(size, 0), recv_displ(size, 0);
  MPI_Alltoall(send_count.data(), 1, MPI_INT, recv_count.data(), 1, MPI_INT, PETSC_COMM_WORLD);
  for (int r = 1; r < size; ++r) {
    send_displ[r] = send_displ[r - 1] + send_count[r - 1];
    recv_displ[r] = recv_displ[r - 1] + recv_count[r - 1];
  }
  std::vector<double> recv(static_cast<std::size_t>(recv_displ[size - 1]) + recv_count[size - 1]);
  MPI_Alltoallv(send.data(), send_count.data(), send_displ.data(), MPI_DOUBLE, recv.data(), recv_count.data(),
                recv_displ.data(), MPI_DOUBLE, PETSC_COMM_WORLD);
  send.clear(), send.shrink_to_fit();

  // Received rows come from several ranks, each in key order: sort them once more.
  const std::size_t m = recv.size() / stride;
  std::vector<Keyed> mine(m);
  for (std::size_t k = 0; k < m; ++k) {
    const double* row = &recv[k * stride + 2 * D + 4];
    mine[k] = {static_cast<std::uint64_t>(row[1]) << 32 | static_cast<std::uint64_t>(row[2]),
               static_cast<GlobalIndex>(row[0]), k};
  }
  std::sort(mine.begin(), mine.end());

  P.n_owned = m;
  P.set_ghost_count(0);
  fields = P.fields.with(kCarried, m);  // resized to the new owned count
  for (std::size_t i = 0; i < m; ++i) {
    const double* row = &recv[mine[i].slot * stride];
    for (int a = 0; a < D; ++a) P.x[i][a] = *row++;
    for (int a = 0; a < D; ++a) P.v[i][a] = *row++;
    P.m[i] = *row++, P.rho[i] = *row++, P.p[i] = *row++;
    P.kind[i] = static_cast<int>(*row++);
    P.id[i] = static_cast<GlobalIndex>(*row++);
    row += 2;  // the key
    for (const ParticleField& f : fields)
      for (int c = 0; c < f.components; ++c) f.data[i * f.components + c] = *row++;
  }
  assign_global_indices(P);

  long long most = static_cast<long long>(m);
  MPI_Allreduce(MPI_IN_PLACE, &most, 1, MPI_LONG_LONG, MPI_MAX, PETSC_COMM_WORLD);
  return P.n_global > 0 ? double(most) * size / double(P.n_global) : 1.0;
}

}  // namespace

template <int D> std::uint64_t morton_key(const Vector<D>& x, const Vector<D>& lo, const Vector<D>& hi) {
  const double cells = std::ldexp(1.0, kBits<D>);
  std::uint64_t key = 0;
  for (int a = 0; a < D; ++a) {
    const double extent = hi[a] - lo[a];
    const double f = extent > 0 ? (x[a] - lo[a]) / extent : 0.0;
    const double c = std::clamp(std::floor(f * cells), 0.0, cells - 1.0);
    key |= spread_bits<D>(static_cast<std::uint64_t>(c)) << a;
  }
  return key;
}

template <int D> double partition_along_curve(Particles<D>& P, const Domain<D>& domain) {
  PetscMPIInt size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  const std::size_t n = P.n_owned;
  for (std::size_t i = 0; i < n; ++i) P.x[i] = domain.wrap(P.x[i]);

  // The curve runs through the bounding box of all particles.
  Vector<D> lo = Vector<D>::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (std::size_t i = 0; i < n; ++i) lo = lo.cwiseMin(P.x[i]), hi = hi.cwiseMax(P.x[i]);
  MPI_Allreduce(MPI_IN_PLACE, lo.data(), D, MPI_DOUBLE, MPI_MIN, PETSC_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, hi.data(), D, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
  std::vector<std::uint64_t> key(n);
  for (std::size_t i = 0; i < n; ++i) key[i] = morton_key<D>(P.x[i], lo, hi);
  std::vector<std::uint64_t> sorted = key;
  std::sort(sorted.begin(), sorted.end());

  // Splitters: rank r receives the keys in [split[r-1], split[r]). Each split[r] is the smallest key
  // value with at least r N / size particles below it, found by bisection on the key range (64 rounds
  // of one reduction, whatever the rank count).
  const GlobalIndex total = P.n_global;
  std::vector<std::uint64_t> split_lo(size > 1 ? size - 1 : 0, 0), split_hi(split_lo.size(), 1ull << 63);
  std::vector<long long> below(split_lo.size());
  for (int round = 0; round < 64 && !split_lo.empty(); ++round) {
    for (std::size_t r = 0; r < split_lo.size(); ++r) {
      const std::uint64_t mid = split_lo[r] + (split_hi[r] - split_lo[r]) / 2;
      below[r] = std::lower_bound(sorted.begin(), sorted.end(), mid) - sorted.begin();
    }
    MPI_Allreduce(MPI_IN_PLACE, below.data(), static_cast<int>(below.size()), MPI_LONG_LONG, MPI_SUM, PETSC_COMM_WORLD);
    for (std::size_t r = 0; r < split_lo.size(); ++r) {
      const std::uint64_t mid = split_lo[r] + (split_hi[r] - split_lo[r]) / 2;
      const long long target = static_cast<long long>(total) * static_cast<long long>(r + 1) / size;
      if (below[r] >= target) split_hi[r] = mid;
      else split_lo[r] = mid + 1;
    }
  }
  std::vector<int> dest(n);
  for (std::size_t i = 0; i < n; ++i)
    dest[i] = static_cast<int>(std::upper_bound(split_hi.begin(), split_hi.end(), key[i]) - split_hi.begin());
  return migrate(P, dest, key);
}

template <int D>
double restore_order(Particles<D>& P, const std::vector<GlobalIndex>& place, const std::vector<GlobalIndex>& owned) {
  const char* kMisfit = "internal error: the recorded order of the particles does not fit them";
  PetscMPIInt size, rank;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  // end[r]: one past the last global index rank r held.
  std::vector<GlobalIndex> end(owned.size());
  std::partial_sum(owned.begin(), owned.end(), end.begin());
  int valid = static_cast<int>(owned.size()) == size && !end.empty() && end.back() == P.n_global;
  std::vector<int> dest(P.n_owned);
  std::vector<std::uint64_t> key(P.n_owned);
  for (std::size_t i = 0; i < P.n_owned && valid; ++i) {
    valid = place[i] >= 0 && place[i] < P.n_global;
    dest[i] = static_cast<int>(std::upper_bound(end.begin(), end.end(), place[i]) - end.begin());
    key[i] = static_cast<std::uint64_t>(place[i]);
  }
  MPI_Allreduce(MPI_IN_PLACE, &valid, 1, MPI_INT, MPI_MIN, PETSC_COMM_WORLD);
  if (!valid) throw Error(kMisfit);
  const double imbalance = migrate(P, dest, key);
  int placed = static_cast<GlobalIndex>(P.n_owned) == owned[rank];
  MPI_Allreduce(MPI_IN_PLACE, &placed, 1, MPI_INT, MPI_MIN, PETSC_COMM_WORLD);
  if (!placed) throw Error(kMisfit);
  return imbalance;
}

template std::uint64_t morton_key<1>(const Vector<1>&, const Vector<1>&, const Vector<1>&);
template std::uint64_t morton_key<2>(const Vector<2>&, const Vector<2>&, const Vector<2>&);
template std::uint64_t morton_key<3>(const Vector<3>&, const Vector<3>&, const Vector<3>&);
template double partition_along_curve<1>(Particles<1>&, const Domain<1>&);
template double partition_along_curve<2>(Particles<2>&, const Domain<2>&);
template double partition_along_curve<3>(Particles<3>&, const Domain<3>&);
template double restore_order<1>(Particles<1>&, const std::vector<GlobalIndex>&, const std::vector<GlobalIndex>&);
template double restore_order<2>(Particles<2>&, const std::vector<GlobalIndex>&, const std::vector<GlobalIndex>&);
template double restore_order<3>(Particles<3>&, const std::vector<GlobalIndex>&, const std::vector<GlobalIndex>&);

}  // namespace sph
