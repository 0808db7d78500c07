#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "operator_lattice.hpp"
#include "solvers/compressible/pruned_pairs.hpp"
#include "src/neighbours/neighbourhood.hpp"
#include "src/sph/operators.hpp"
#include "src/sph/pair_loop.hpp"

namespace {

using namespace sph;
using namespace sph::test;

// The pair loop gathers each particle's pairs into a batch before the pair functions see them
// (src/sph/pair_loop.hpp). Against a brute-force search over every two particles: it visits exactly
// the pairs inside the support, in increasing j, with the kernel's W, dW/dr and gradient of each
// pair, from Verlet lists whose skin holds candidates outside the support. A pair function that runs
// another particle's pairs (a nested loop) sees them whole and leaves the outer batch intact.
TEST(PairLoop, BatchesHoldExactlyThePairsOfABruteForceSearch) {
  struct Seen {
    int j;
    double r, W, dWdr;
    V2 gradW;
    bool operator==(const Seen& o) const {
      return j == o.j && r == o.r && W == o.W && dWdr == o.dWdr && gradW == o.gradW;
    }
  };
  for (const KernelCase& kc : kCases) {
    SCOPED_TRACE(label(kc));
    Patch S(12, kc);
    const double R = S.K.support_radius();
    Neighbourhood<2> skinned(S.domain, R, 0.4 * R);
    skinned.update(S.P, true);
    const std::size_t n = S.P.n_owned;
    std::vector<std::vector<Seen>> expected(n), seen(n);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j) {
        const V2 rij = S.P.x[i] - S.P.x[j];
        const double r2 = rij.squaredNorm(), r = std::sqrt(r2);
        if (j == i || !(r2 < R * R)) continue;
        expected[i].push_back({static_cast<int>(j), r, S.K.W(r), S.K.dWdr(r), V2((S.K.dWdr(r) / r) * rij)});
      }
    std::size_t candidates = 0;
    for (std::size_t i = 0; i < n; ++i) candidates += skinned.list().count(i);
    std::size_t pairs = 0;
    for (const auto& e : expected) pairs += e.size();
    ASSERT_GT(candidates, pairs + pairs / 4) << "the skin must hold candidates outside the support";

    const double rc2 = R * R;
    std::vector<std::size_t> nested_count(n, 0);
    for_each_particle_pairs(S.P, skinned.list(), S.K, [&](std::size_t i, auto&& visit_pairs) {
      visit_pairs([&](int, int j, const PairGeometry<2>& g) {
        seen[i].push_back({j, g.r, g.W, g.dWdr, g.gradW});
        // A nested loop over j's pairs, in the middle of i's.
        std::size_t count = 0;
        auto counter = [&](int, int, const PairGeometry<2>&) { ++count; };
        detail::pairs_of(static_cast<std::size_t>(j), S.P, skinned.list(), S.K, rc2, counter);
        if (count != expected[static_cast<std::size_t>(j)].size()) ++nested_count[i];
      });
    });
    for (std::size_t i = 0; i < n; ++i) {
      ASSERT_EQ(seen[i].size(), expected[i].size()) << "particle " << i;
      for (std::size_t k = 0; k < seen[i].size(); ++k) EXPECT_TRUE(seen[i][k] == expected[i][k]) << i << " pair " << k;
      EXPECT_EQ(nested_count[i], 0u) << "particle " << i << ": a nested loop saw a wrong pair count";
    }
  }
}

}  // namespace

namespace {

// The ghost check (src/neighbours/ghost_check.hpp), which every test binary and every run of the test
// suite has on: on the periodic lattice, whose ghosts are periodic images, a value written on an owned
// particle and not refreshed stops the next pair loop with a message naming the field, the particles'
// own fields and an operator's field alike; refreshed, the loop runs. With the checks off nothing is
// compared.
TEST(GhostCheck, APairLoopStopsAtGhostsThatMissedAWrite) {
  ASSERT_TRUE(ghost_checks());
  Lattice L(16, kCases[0]);
  ASSERT_GT(L.P.n_ghost, 0u);
  const std::vector<V2> u = L.sample<V2>(u_tg);
  EXPECT_NO_THROW(divergence(L.P, L.nl(), L.K, u));
  // Particle 0 sits in a corner: every periodic image of it is a ghost.
  L.P.p[0] += 1.0;
  try {
    divergence(L.P, L.nl(), L.K, u);
    ADD_FAILURE() << "a stale pressure ghost went unnoticed";
  } catch (const std::logic_error& e) {
    EXPECT_NE(std::string(e.what()).find("ghost copies of p "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("test_pair_loop.cpp"), std::string::npos) << "the caller: " << e.what();
  }
  L.nh->halo().update(L.P.p);
  EXPECT_NO_THROW(divergence(L.P, L.nl(), L.K, u));

  std::vector<V2> w = u;
  w[0] *= 2.0;
  EXPECT_THROW(divergence(L.P, L.nl(), L.K, w), std::logic_error);
  ghost_checks() = false;
  EXPECT_NO_THROW(divergence(L.P, L.nl(), L.K, w));
  ghost_checks() = true;
  L.nh->halo().update(w);
  EXPECT_NO_THROW(divergence(L.P, L.nl(), L.K, w));
}

// Marked writes (Particles::written): a particle column or a registry field written on owned particles
// and marked is fresh in the ghosts of the next pair loop or ghost check, and the marks are spent; a
// step-local field cannot be marked (its owner refreshes it); a rebuild leaves no particle column marked.
TEST(GhostCheck, AMarkedWriteIsFreshInTheNextPairLoop) {
  ASSERT_TRUE(ghost_checks());
  Lattice L(16, kCases[0]);
  ASSERT_GT(L.P.n_ghost, 0u);
  const std::vector<V2> u = L.sample<V2>(u_tg);
  const FieldId<double> q = L.P.fields.declare_scalar("q", kCarried, L.P.size());
  L.P.p[0] += 1.0, L.P.v[0] *= 2.0, L.P.fields[q][0] = 3.0;
  L.P.written(L.P.p), L.P.written(L.P.v), L.P.written(L.P.fields[q]);
  EXPECT_TRUE(L.P.stale.any());
  EXPECT_NO_THROW(divergence(L.P, L.nl(), L.K, u));  // the loop refreshes them first
  EXPECT_FALSE(L.P.stale.any());
  EXPECT_NO_THROW(check_ghosts(L.nl(), L.P.fields[q], "q"));
  // Fresh bit for bit (the checks compare with a new copy), and particle 0's images hold its new values.
  EXPECT_NO_THROW(check_ghosts(L.nl(), L.P.p, "p"));
  EXPECT_NO_THROW(check_ghosts(L.nl(), L.P.v, "v"));
  std::size_t images = 0;
  for (std::size_t g = L.P.n_owned; g < L.P.size(); ++g)
    images += L.P.p[g] == L.P.p[0] && L.P.v[g] == L.P.v[0] && L.P.fields[q][g] == 3.0;
  EXPECT_GT(images, 0u);
  // A ghost check on a marked field refreshes it too (a function that reads ghost slots directly
  // checks its fields first).
  L.P.fields[q][0] = 4.0;
  L.P.written(L.P.fields[q]);
  EXPECT_NO_THROW(check_ghosts(L.nl(), L.P.fields[q], "q"));
  std::vector<double> local(L.P.size(), 0.0);
  EXPECT_THROW(L.P.written(local), std::logic_error);
  L.P.rho[0] *= 1.5;
  L.P.written(L.P.rho);
  L.nh->update(L.P, true);
  EXPECT_FALSE(L.P.stale.any());
}

// The compressible solver's variable-h loop runs over its pruned lists, which know the halo of the
// list they were pruned from: a stale ghost stops it too.
TEST(GhostCheck, TheVariableHLoopStopsAtGhostsThatMissedAWrite) {
  ASSERT_TRUE(ghost_checks());
  Lattice L(16, kCases[0]);
  const std::vector<double> h(L.P.size(), L.K.h());
  const double kappa = L.K.support_radius() / L.K.h();
  compressible::PrunedPairs<2> pairs;
  pairs.build(L.P, L.nl(), h, kappa, 1.0);
  ASSERT_EQ(pairs.halo(), L.nl().halo());
  const std::vector<Kernel<2>> kernels(L.P.size(), L.K);
  std::vector<std::size_t> visited(L.P.n_owned, 0);  // threads share the particles i
  auto count = [&](int i, int, const VariableHPair<2>&) { ++visited[static_cast<std::size_t>(i)]; };
  EXPECT_NO_THROW(for_each_variable_h_pair(L.P, pairs, kernels, count));
  for (std::size_t i = 0; i < L.P.n_owned; ++i) EXPECT_EQ(visited[i], pairs.count(i)) << "particle " << i;
  L.P.rho[0] *= 1.01;
  try {
    for_each_variable_h_pair(L.P, pairs, kernels, count);
    ADD_FAILURE() << "a stale density ghost went unnoticed";
  } catch (const std::logic_error& e) {
    EXPECT_NE(std::string(e.what()).find("ghost copies of rho "), std::string::npos) << e.what();
  }
  L.nh->halo().update(L.P.rho);
  EXPECT_NO_THROW(for_each_variable_h_pair(L.P, pairs, kernels, count));
}

}  // namespace
