// Domain decomposition on any rank count (CTest runs this file on 1 rank and under mpiexec on 3):
// the space-filling-curve partition keeps every particle exactly once, balances the counts, gives
// each rank a contiguous stretch of the curve and carries per-particle solver arrays along; the
// cross-rank halo plus neighbour lists find exactly the pairs a brute-force search over all particles
// (gathered from every rank, with periodic images) finds; checkpoints come back by particle label
// whatever the partition.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <vector>

#include "random_points.hpp"
#include "src/io/checkpoint.hpp"
#include "src/neighbours/neighbourhood.hpp"
#include "src/neighbours/partition.hpp"
#include "src/particles/global_indices.hpp"
#include "src/run/box_exit.hpp"

namespace {

using namespace sph;

int rank() {
  int r;
  MPI_Comm_rank(PETSC_COMM_WORLD, &r);
  return r;
}
int ranks() {
  int s;
  MPI_Comm_size(PETSC_COMM_WORLD, &s);
  return s;
}

template <int D> Domain<D> box(std::array<bool, D> periodic) {
  Domain<D> d;
  for (int a = 0; a < D; ++a) d.lo[a] = -0.2 * a, d.hi[a] = d.lo[a] + 1.0 + 0.1 * a;
  d.periodic = periodic;
  return d;
}

// Random particles: every rank draws the same global set and keeps a deliberately bad share
// (every ranks()-th particle), so the partition has to move almost everything.
template <int D> Particles<D> scattered_particles(const Domain<D>& dom, int n, unsigned seed) {
  const std::vector<Vector<D>> points = test::random_points(dom, n, seed);
  Particles<D> P;
  for (int k = 0; k < n; ++k)
    if (k % ranks() == rank()) P.add(points[k], Vector<D>::Zero(), 1.0, 1.0, 0.0);
  assign_global_indices(P);
  for (std::size_t i = 0; i < P.n_owned; ++i) P.v[i] = Vector<D>::Constant(static_cast<double>(P.id[i]));
  return P;
}

template <int D> std::vector<double> gather_positions(const Particles<D>& P, std::vector<long long>& ids) {
  std::vector<double> mine;
  std::vector<long long> my_ids;
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    for (int a = 0; a < D; ++a) mine.push_back(P.x[i][a]);
    my_ids.push_back(P.id[i]);
  }
  int count = static_cast<int>(my_ids.size());
  std::vector<int> counts(ranks()), displ(ranks(), 0);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, PETSC_COMM_WORLD);
  for (int r = 1; r < ranks(); ++r) displ[r] = displ[r - 1] + counts[r - 1];
  ids.resize(displ.back() + counts.back());
  MPI_Allgatherv(my_ids.data(), count, MPI_LONG_LONG, ids.data(), counts.data(), displ.data(), MPI_LONG_LONG,
                 PETSC_COMM_WORLD);
  for (int r = 0; r < ranks(); ++r) counts[r] *= D, displ[r] *= D;
  std::vector<double> all(ids.size() * D);
  MPI_Allgatherv(mine.data(), count * D, MPI_DOUBLE, all.data(), counts.data(), displ.data(), MPI_DOUBLE,
                 PETSC_COMM_WORLD);
  return all;
}

TEST(Partition, KeepsEveryParticleOnceBalancedAndContiguousAlongTheCurve) {
  const Domain<2> dom = box<2>({true, false});
  const int n = 1001;
  Particles<2> P = scattered_particles(dom, n, 3u);
  // A scheme's carried field (2 components) whose values identify the particle they belong to, and
  // one that is not carried.
  const FieldId<Vector<2>> acc = P.fields.declare_vector("acc", kCarried, P.size());
  const FieldId<double> scratch = P.fields.declare_scalar("scratch", 0u, P.size());
  for (std::size_t i = 0; i < P.n_owned; ++i) P.fields[acc][i] = Vector<2>(P.id[i], -2.0 * P.id[i]);
  const double imbalance = partition_along_curve(P, dom);

  std::vector<long long> ids;
  const std::vector<double> x = gather_positions(P, ids);
  ASSERT_EQ(ids.size(), static_cast<std::size_t>(n));
  EXPECT_EQ(std::set<long long>(ids.begin(), ids.end()).size(), static_cast<std::size_t>(n));
  // Equal shares: n = 1001 is not a multiple of 2 or 3, so shares differ by one at most.
  EXPECT_LE(imbalance, (n / ranks() + 1.0) * ranks() / n + 1e-12);
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    EXPECT_EQ(P.gid[i], P.first_gid + static_cast<GlobalIndex>(i));
    EXPECT_EQ(P.v[i][0], static_cast<double>(P.id[i])) << "particle data travels with the particle";
    EXPECT_EQ(P.fields[acc][i], Vector<2>(P.id[i], -2.0 * P.id[i])) << "carried fields travel with the particle";
  }
  // Along the curve: keys increase within a rank and from one rank to the next.
  Vector<2> lo = Vector<2>::Constant(1e300), hi = -lo;
  for (std::size_t k = 0; k < ids.size(); ++k)
    lo = lo.cwiseMin(Vector<2>(x[2 * k], x[2 * k + 1])), hi = hi.cwiseMax(Vector<2>(x[2 * k], x[2 * k + 1]));
  std::vector<std::uint64_t> keys;
  for (std::size_t k = 0; k < ids.size(); ++k) keys.push_back(morton_key<2>(Vector<2>(x[2 * k], x[2 * k + 1]), lo, hi));
  EXPECT_TRUE(std::is_sorted(keys.begin(), keys.end()));
  // Re-partitioning a partitioned set changes nothing.
  const std::vector<GlobalIndex> before(P.id.begin(), P.id.begin() + P.n_owned);
  EXPECT_EQ(P.fields[scratch].size(), P.size()) << "every declared field is sized with the particles";
  partition_along_curve(P, dom);
  EXPECT_EQ(before, std::vector<GlobalIndex>(P.id.begin(), P.id.begin() + P.n_owned));
}

// A checkpoint's record of the order (each particle's global index, each rank's count) puts every
// particle back on its rank and at its place after another partition, with its carried fields and
// its position as it is (not wrapped into the periodic box); a record that does not fit is refused.
TEST(Partition, RestoresARecordedOrder) {
  const Domain<2> dom = box<2>({true, false});
  Particles<2> P = scattered_particles(dom, 1001, 5u);
  const FieldId<double> place = P.fields.declare_scalar("place", kCarried, P.size());
  const FieldId<Vector<2>> x0 = P.fields.declare_vector("x0", kCarried, P.size());
  partition_along_curve(P, dom);
  for (std::size_t i = 0; i < P.n_owned; ++i) P.fields[place][i] = static_cast<double>(P.gid[i]);
  const std::vector<GlobalIndex> ids(P.id.begin(), P.id.begin() + P.n_owned);
  std::vector<GlobalIndex> owned(ranks());
  const GlobalIndex n_owned = static_cast<GlobalIndex>(P.n_owned);
  MPI_Allgather(&n_owned, 1, MPIU_INT, owned.data(), 1, MPIU_INT, PETSC_COMM_WORLD);

  // Another order: the particles mirrored, re-partitioned, then put back where they were, one of them
  // a period further on.
  for (std::size_t i = 0; i < P.n_owned; ++i) P.fields[x0][i] = P.x[i], P.x[i][1] = 0.7 - P.x[i][1];
  partition_along_curve(P, dom);
  ASSERT_NE(ids, std::vector<GlobalIndex>(P.id.begin(), P.id.begin() + P.n_owned));
  if (P.n_owned > 0) P.fields[x0][0][0] += dom.length()[0];
  std::vector<GlobalIndex> recorded(P.n_owned), wrong(P.n_owned);
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    P.x[i] = P.fields[x0][i];
    recorded[i] = wrong[i] = static_cast<GlobalIndex>(P.fields[place][i]);
  }
  if (!wrong.empty()) wrong[0] = P.n_global;  // beyond the last place
  EXPECT_THROW(restore_order(P, wrong, owned), Error);
  std::vector<GlobalIndex> short_by_one = owned;
  short_by_one.back() -= 1;
  EXPECT_THROW(restore_order(P, recorded, short_by_one), Error);

  restore_order(P, recorded, owned);
  EXPECT_EQ(ids, std::vector<GlobalIndex>(P.id.begin(), P.id.begin() + P.n_owned));
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    EXPECT_EQ(P.gid[i], static_cast<GlobalIndex>(P.fields[place][i]));
    EXPECT_EQ(P.x[i], P.fields[x0][i]) << "positions are not wrapped";
  }
}

TEST(Partition, MortonKeysInterleaveTheAxes) {
  const Vector<2> lo(0, 0), hi(1, 1);
  // The four quadrants in Z order: (0,0) < (1,0) < (0,1) < (1,1).
  const auto k = [&](double x, double y) { return morton_key<2>(Vector<2>(x, y), lo, hi); };
  EXPECT_LT(k(0.1, 0.1), k(0.9, 0.1));
  EXPECT_LT(k(0.9, 0.1), k(0.1, 0.9));
  EXPECT_LT(k(0.1, 0.9), k(0.9, 0.9));
  EXPECT_EQ(k(0.0, 0.0), 0u);
  EXPECT_LT(k(1.0, 1.0), 1ull << 63);
}

// Every pair within the support, as (id_i, id_j, rounded separation vector), from the halo and lists.
template <int D>
std::set<std::vector<long long>> pairs_found(const Particles<D>& P, const Neighbourhood<D>& nh, double rc) {
  std::set<std::vector<long long>> found;
  const NeighbourList<D>& nl = nh.list();
  for (std::size_t i = 0; i < P.n_owned; ++i)
    for (const int* it = nl.begin(i); it != nl.end(i); ++it) {
      const Vector<D> r = P.x[i] - P.x[*it];
      if (r.norm() >= rc) continue;
      std::vector<long long> key = {P.id[i], P.id[*it]};
      for (int a = 0; a < D; ++a) key.push_back(std::llround(r[a] * 1e9));
      found.insert(key);
    }
  return found;
}

template <int D> void check_pairs_against_brute_force(std::array<bool, D> periodic, int n, double rc) {
  const Domain<D> dom = box<D>(periodic);
  Particles<D> P = scattered_particles(dom, n, 11u + D);
  partition_along_curve(P, dom);
  Neighbourhood<D> nh(dom, rc, 0.1 * rc);
  nh.update(P, true);
  // Ghost fields are the owners' values (velocity encodes the label).
  for (std::size_t g = P.n_owned; g < P.size(); ++g) EXPECT_EQ(P.v[g][0], static_cast<double>(P.id[g]));

  std::vector<long long> ids;
  const std::vector<double> all = gather_positions(P, ids);
  const Vector<D> L = dom.length();
  std::set<std::vector<long long>> expected;
  for (std::size_t i = 0; i < P.n_owned; ++i)
    for (std::size_t k = 0; k < ids.size(); ++k) {
      Vector<D> r;
      for (int a = 0; a < D; ++a) {
        r[a] = P.x[i][a] - all[k * D + a];
        if (dom.periodic[a]) r[a] -= L[a] * std::round(r[a] / L[a]);  // nearest image (box > 2 rc)
      }
      if (ids[k] == P.id[i] || r.norm() >= rc) continue;
      std::vector<long long> key = {P.id[i], ids[k]};
      for (int a = 0; a < D; ++a) key.push_back(std::llround(r[a] * 1e9));
      expected.insert(key);
    }
  const auto found = pairs_found(P, nh, rc);
  EXPECT_EQ(found.size(), expected.size()) << "rank " << rank();
  EXPECT_TRUE(found == expected) << "rank " << rank();
}

TEST(ParallelHalo, PairsMatchBruteForceIn2DPeriodicAndWalled) {
  check_pairs_against_brute_force<2>({true, true}, 900, 0.12);
  check_pairs_against_brute_force<2>({false, true}, 900, 0.12);
}

TEST(ParallelHalo, PairsMatchBruteForceIn3DAnd1D) {
  check_pairs_against_brute_force<3>({true, false, true}, 1500, 0.2);
  check_pairs_against_brute_force<1>({true}, 300, 0.02);
}

TEST(Partition, RemovalTakesTheDeclaredFieldsRowsAlong) {
  const Domain<2> dom = box<2>({true, true});
  Particles<2> P = scattered_particles(dom, 300, 7u);
  const FieldId<Vector<2>> acc = P.fields.declare_vector("acc", kCarried, P.size());
  const FieldId<double> flag = P.fields.declare_scalar("flag", kCarried | kWritten, P.size());
  for (std::size_t i = 0; i < P.n_owned; ++i) P.fields[acc][i] = Vector<2>(P.id[i], 1.0), P.fields[flag][i] = -P.id[i];
  const RemovedFluid gone = remove_particles_if(P, [&](std::size_t i) { return P.id[i] % 3 == 0; });
  EXPECT_EQ(gone.count, 100);
  EXPECT_EQ(P.n_global, 200);
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    EXPECT_NE(P.id[i] % 3, 0);
    EXPECT_EQ(P.fields[acc][i], Vector<2>(P.id[i], 1.0));
    EXPECT_EQ(P.fields[flag][i], -static_cast<double>(P.id[i]));
  }
  EXPECT_EQ(P.fields.find_scalar("flag", kWritten), &P.fields[flag]);
  EXPECT_EQ(P.fields.find_scalar("flag", kCarried), &P.fields[flag]);
  EXPECT_EQ(P.fields.find_scalar("acc", kCarried), nullptr) << "a vector field is not a scalar";
}

TEST(ParallelCheckpoint, FieldsComeBackByLabelWhateverThePartition) {
  const Domain<2> dom = box<2>({true, true});
  Particles<2> P = scattered_particles(dom, 500, 5u);
  const FieldId<double> extra = P.fields.declare_scalar("extra", kCarried, P.size());
  P.fields.declare_scalar("scratch", 0u, P.size());  // not saved
  for (std::size_t i = 0; i < P.n_owned; ++i) P.fields[extra][i] = 0.5 * P.id[i];
  const std::string dir = std::string(SPH_BINARY_DIR) + "/test-output/parallel_checkpoint_" + std::to_string(ranks());
  if (rank() == 0) std::filesystem::create_directories(dir);
  MPI_Barrier(PETSC_COMM_WORLD);
  write_checkpoint(dir + "/c.bin", P, CheckpointState<2>{});

  // The same particles in another split and order, with scrambled fields, read the file back.
  Particles<2> Q = scattered_particles(dom, 500, 5u);
  partition_along_curve(Q, dom);
  const std::vector<Vector<2>> x_expected(Q.x.begin(), Q.x.begin() + Q.n_owned);
  for (std::size_t i = 0; i < Q.n_owned; ++i) Q.x[i].setZero(), Q.v[i].setZero();
  const FieldId<double> extra_q = Q.fields.declare_scalar("extra", kCarried, Q.size());
  for (std::size_t i = 0; i < Q.n_owned; ++i) Q.fields[extra_q][i] = -1.0;
  read_checkpoint(dir + "/c.bin", Q);
  for (std::size_t i = 0; i < Q.n_owned; ++i) {
    EXPECT_EQ(Q.x[i], x_expected[i]);
    EXPECT_EQ(Q.v[i][0], static_cast<double>(Q.id[i]));
    EXPECT_EQ(Q.fields[extra_q][i], 0.5 * Q.id[i]);
  }
}

}  // namespace
