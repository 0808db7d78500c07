#pragma once
// The consistent Laplacian (consistent_laplacian.hpp) is exact for quadratics; on a smooth field its
// leading error is its weights' fourth moments times the field's fourth derivatives: the kernel's
// smoothing error, O(h^2), which makes a viscous vortex decay too slowly (Taylor-Green: over 90 % of
// ISPH's velocity error; docs/verification/speed_against_error.md). Where the fourth moments are
// isotropic, sum_j w_ij r r r r = mu (d_ab d_cd + d_ac d_bd + d_ad d_bc), that error is (mu / 8) lap^2 f,
// with mu = sum_j w_ij |r|^4 / (D (D + 2)). So
//   lap f_i - beta_i lap(lap f)_i,   beta_i = sum_j w_ij |r_ij|^4 / (8 D (D + 2)),
// with lap applied again by the same weights, removes it: a deconvolution of the kernel's smoothing,
// one more pass over the pairs (its effect on the errors: the page above).
//
// Only at particles whose support holds no wall particle: beside a wall lap f_j of a wall particle
// does not exist (walls carry extrapolated values, not operators). Callers leave it off where a free
// surface cuts the supports (the one-sided weights there are not isotropic).
#include <vector>

#include "src/neighbours/neighbourhood.hpp"
#include "src/sph/consistent_laplacian.hpp"

namespace sph {

// Which viscous Laplacian a solver uses (-viscous_laplacian): second, the consistent Laplacian as it
// is; fourth, with its smoothing error removed (above).
enum class ViscousLaplacian { Second, Fourth };
inline const char* const viscous_laplacian_names[] = {"second", "fourth"};
inline const char* const viscous_laplacian_help =
    "Viscous Laplacian: second (the consistent Laplacian, exact for quadratics, O(h^2) smoothing error) or fourth "
    "(its smoothing error removed by lap - beta lap^2 where no wall is in the support; off in free-surface scenes). "
    "Default: fourth for ISPH, second for WCSPH";

// For summary.json's models: whether a run's viscous term removed its smoothing error.
inline const char* smoothing_error_description(bool removed) {
  return removed ? "removed away from walls (lap - beta lap^2)" : "kept (second order)";
}

// lap (the consistent Laplacian of a field, owned particles, computed with `factors`) minus its
// smoothing error, in place, at the fluid particles with no wall particle in their support.
template <int D>
void remove_laplacian_smoothing_error(const Particles<D>& P, const Neighbourhood<D>& nh, const Kernel<D>& K,
                                      const std::vector<LaplacianCorrection<D>>& factors, std::vector<Vector<D>>& lap) {
  std::vector<Vector<D>> lap_all(P.size(), Vector<D>::Zero());  // with the ghosts' values
  std::copy(lap.begin(), lap.begin() + P.n_owned, lap_all.begin());
  nh.halo().update(lap_all);
  struct Sums {
    Vector<D> lap2 = Vector<D>::Zero();
    double m4 = 0.0;
    bool wall = false;
  };
  const std::vector<Sums> sums = sum_over_pairs(
      P, nh.list(), K, Sums{},
      [&](Sums& s, int i, int j, const PairGeometry<D>& g) {
        if (P.kind[j] != kFluid) {
          s.wall = true;
          return;
        }
        const double w = consistent_laplacian_coefficient(factors[i], P.m[j] / P.rho[j], g);
        const double r2 = g.r * g.r;
        s.lap2 += w * (lap_all[j] - lap_all[i]);
        s.m4 += w * r2 * r2;
      },
      Rows::Fluid);
  constexpr double isotropic = 1.0 / (8.0 * D * (D + 2));
  for (std::size_t i = 0; i < P.n_owned; ++i)
    if (P.kind[i] == kFluid && !sums[i].wall) lap[i] -= (isotropic * sums[i].m4) * sums[i].lap2;
}

}  // namespace sph
