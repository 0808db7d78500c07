// Shared-memory threading must not change results: the pair loops give every particle's sums in list
// order on one thread, the threaded neighbour search joins its blocks in order, and the pressure
// Poisson rows (walls and Dirichlet rows among them) are each built on one thread. So 1 thread and
// several threads must agree bitwise, on a disordered periodic cloud in 2D and 3D (brute-force
// equality, no tolerance). A build without OpenMP runs the same code on one thread and passes trivially.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "solvers/isph/ppe_rows.hpp"
#include "src/core/domain.hpp"
#include "src/kernels/kernel.hpp"
#include "src/neighbours/neighbourhood.hpp"
#include "src/particles/particles.hpp"
#include "src/run/threads.hpp"
#include "src/sph/operators.hpp"

namespace {

using namespace sph;

// Everything the threaded code computes, for one thread count.
template <int D> struct Results {
  std::vector<std::size_t> list_offsets;
  std::vector<int> list_index;
  std::vector<double> rho, div;
  std::vector<Vector<D>> grad, lap;
  std::vector<Tensor<D>> L;
  PpeRows ppe;
};

template <int D> Results<D> compute(int threads, int n_side) {
  configure_threads(threads);
  const double dx = 1.0 / n_side;
  Kernel<D> K(KernelType::WendlandC2, 1.5 * dx);
  Domain<D> domain;
  domain.periodic.fill(true);
  Particles<D> P;
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> jitter(-0.2 * dx, 0.2 * dx);
  int total = 1;
  for (int d = 0; d < D; ++d) total *= n_side;
  for (int k = 0; k < total; ++k) {
    Vector<D> x;
    for (int d = 0, r = k; d < D; ++d, r /= n_side) x[d] = (r % n_side + 0.5) * dx + jitter(gen);
    P.add(x, Vector<D>::Zero(), std::pow(dx, D), 1.0 + 0.1 * jitter(gen) / dx, 0.0, k % 11 == 0 ? kWall : kFluid);
    P.gid.back() = k;
  }
  P.n_global = total;
  Neighbourhood<D> nh(domain, K.support_radius(), 0.1 * K.support_radius());
  nh.update(P, true);
  std::vector<double> f(P.n_owned);
  std::vector<Vector<D>> u(P.n_owned);
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    f[i] = std::sin(6.0 * P.x[i][0]) + P.x[i].squaredNorm();
    for (int d = 0; d < D; ++d) u[i][d] = std::cos(4.0 * P.x[i][(d + 1) % D]);
  }
  nh.halo().update(f);
  nh.halo().update(u);
  const NeighbourList<D>& nl = nh.list();
  Results<D> r;
  for (std::size_t i = 0; i < nl.size(); ++i) {
    r.list_offsets.push_back(nl.count(i));
    r.list_index.insert(r.list_index.end(), nl.begin(i), nl.end(i));
  }
  r.rho = density_summation(P, nl, K);
  r.div = divergence(P, nl, K, u);
  r.L = correction_matrices(P, nl, K);
  r.grad = gradient_corrected(P, nl, K, r.L, f);
  r.lap = laplacian_morris(P, nl, K, u);
  std::vector<char> dirichlet(P.n_owned, 0);
  for (std::size_t i = 0; i < P.n_owned; i += 17) dirichlet[i] = 1;
  Vector<D> gravity = Vector<D>::Zero();
  gravity[D - 1] = -9.81;
  r.ppe.build(P, nl, K, gravity, dirichlet);
  return r;
}

template <int D> void expect_same_on_any_thread_count(int n_side) {
  const Results<D> one = compute<D>(1, n_side);
  const Results<D> many = compute<D>(3, n_side);  // 3: blocks of unequal length on 2 cores too
#ifdef _OPENMP
  EXPECT_EQ(max_threads(), 3);  // the second run did use several threads
#endif
  ASSERT_EQ(one.list_offsets, many.list_offsets);
  EXPECT_EQ(one.list_index, many.list_index);
  EXPECT_EQ(one.rho, many.rho);
  EXPECT_EQ(one.div, many.div);
  ASSERT_EQ(one.grad.size(), many.grad.size());
  for (std::size_t i = 0; i < one.grad.size(); ++i) {
    EXPECT_EQ(one.grad[i], many.grad[i]) << i;
    EXPECT_EQ(one.lap[i], many.lap[i]) << i;
    EXPECT_EQ(one.L[i], many.L[i]) << i;
  }
  EXPECT_EQ(one.ppe.di, many.ppe.di);
  EXPECT_EQ(one.ppe.dj, many.ppe.dj);
  EXPECT_EQ(one.ppe.da, many.ppe.da);
  EXPECT_EQ(one.ppe.oi, many.ppe.oi);
  EXPECT_EQ(one.ppe.rhs, many.ppe.rhs);
  configure_threads(1);
}

TEST(Threads, PairLoopsAndNeighbourListsAreBitwiseTheSameIn2D) { expect_same_on_any_thread_count<2>(40); }
TEST(Threads, PairLoopsAndNeighbourListsAreBitwiseTheSameIn3D) { expect_same_on_any_thread_count<3>(14); }

}  // namespace
