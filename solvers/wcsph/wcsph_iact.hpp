#pragma once
// Pair physics of weakly-compressible SPH: each function is one i-j interaction, add_rates_pair the
// whole of one pair's contribution to the rates; the loops live in the solver (wcsph_solver.cpp).
#include <cmath>
#include <vector>

#include "src/core/integer_power.hpp"
#include "src/particles/particles.hpp"
#include "src/sph/artificial_viscosity.hpp"
#include "src/sph/consistent_laplacian.hpp"
#include "src/sph/operators.hpp"
#include "src/sph/pair_terms.hpp"

namespace sph::wcsph {

// Tait equation of state (Batchelor 1967; Monaghan 1994): p = B ((rho/rho0)^gamma - 1), B = c0^2 rho0 / gamma.
struct TaitEos {
  double rho0 = 1.0, c0 = 10.0, gamma = 7.0;
  double B() const { return c0 * c0 * rho0 / gamma; }
  double pressure(double rho) const { return B() * (power(rho / rho0, gamma) - 1.0); }
  double density(double p) const { return rho0 * std::pow(1.0 + p / B(), 1.0 / gamma); }
  double sound_speed(double rho) const { return c0 * power(rho / rho0, 0.5 * (gamma - 1.0)); }
  // The specific elastic energy e(rho) = int_rho0^rho p / r^2 dr = (B / rho0) ((s^(gamma-1) - 1) / (gamma - 1)
  // + 1/s - 1), s = rho / rho0, written in s - 1 so that the two O(s - 1) terms cancel without round-off.
  double elastic_energy(double rho) const {
    const double e = rho / rho0 - 1.0;
    return B() / rho0 * (std::expm1((gamma - 1.0) * std::log1p(e)) / (gamma - 1.0) - e / (1.0 + e));
  }
};

// Continuity: d rho_i/dt += rho_i V_j u_ij . grad_i W_ij.
template <int D>
inline double continuity_pair(double rho_i, double Vj, const Vector<D>& uij, const PairGeometry<D>& g) {
  return rho_i * Vj * uij.dot(g.gradW);
}

// Molteni & Colagrossi (2009) density diffusion: delta h c0 sum_j psi_ij . grad_i W_ij V_j with
// psi_ij = 2 (rho_j - rho_i) (x_j - x_i) / |x_j - x_i|^2, i.e. delta h c0 times a Morris Laplacian of rho.
// Antuono et al. (2010) subtract the part a linear density field would give: (G_i + G_j) . grad_i W_ij V_j
// with G the corrected density gradient, so hydrostatic stratification is not diffused.
template <int D> inline double density_diffusion_pair(double delta_h_c0, double rho_i, double rho_j, double Vj,
                                                      double F, const Vector<D>& Gi, const Vector<D>& Gj,
                                                      const PairGeometry<D>& g) {
  return delta_h_c0 * Vj * (-2.0 * (rho_j - rho_i) * F - (Gi + Gj).dot(g.gradW));
}

// Monaghan (1992) artificial viscosity Pi_ij (only for approaching pairs) with WCSPH's sound speeds.
struct MonaghanAV {
  double alpha = 0.0, beta = 0.0, epsilon = 0.01;
  bool active() const { return alpha > 0.0 || beta > 0.0; }
  // The sound speeds come from the equation of state, and only for approaching pairs: std::pow.
  template <int D> double Pi(double h, const TaitEos& eos, double rho_i, double rho_j, const Vector<D>& uij,
                             const PairGeometry<D>& g) const {
    const double ur = uij.dot(g.rij);
    if (ur >= 0.0) return 0.0;
    const double c_mean = 0.5 * (eos.sound_speed(rho_i) + eos.sound_speed(rho_j));
    return monaghan_viscosity(alpha, beta, epsilon, h, c_mean, 0.5 * (rho_i + rho_j), ur, g.r);
  }
};

// Momentum-conserving pressure acceleration on i from j.
template <int D> inline Vector<D> pressure_acceleration_pair(double mj, double pi, double pj, double rho_i,
                                                             double rho_j, const PairGeometry<D>& g) {
  return (-mj * (pi / (rho_i * rho_i) + pj / (rho_j * rho_j))) * g.gradW;
}

// What one fluid particle's pairs add up to in a rates evaluation: the acceleration and density rate,
// and for the corrected forms the sums finished after the loop (moment matrix, pressure-difference
// and velocity-difference gradients).
// Kept by cause, for the energy budget (src/sph/energy_budget.hpp): the pressure's acceleration (acc),
// the artificial and the laminar viscosity's, and the density rate of compression (drho) and diffusion.
template <int D> struct RateSums {
  Vector<D> acc = Vector<D>::Zero(), acc_av = Vector<D>::Zero(), acc_viscous = Vector<D>::Zero(),
            grad_p = Vector<D>::Zero();
  Tensor<D> M = Tensor<D>::Zero(), grad_u = Tensor<D>::Zero();
  double drho = 0.0, drho_diffusion = 0.0;
  FusedConsistentLaplacian<D> viscous;  // the consistent viscous Laplacian's moments and factors
  explicit RateSums(LaplacianPairs<D>& pairs) : viscous(pairs) {}
};

// Which forms of the rates a run evaluates, fixed by its options and physics (WcsphSolver::rate_forms).
struct RateForms {
  bool viscous = false;               // a laminar viscosity (nu > 0)
  bool consistent_viscous = false;    // ... by the consistent Laplacian (else Morris's)
  bool corrected_gradient = false;    // the corrected pressure gradient (else the symmetric force)
  bool continuity = false;            // the density by the continuity equation (else by summation)
  bool corrected_continuity = false;  // ... with the corrected divergence
  bool diffuse = false;               // delta-SPH density diffusion
};

// The fields and settings of one rates evaluation that the pair physics reads.
template <int D> struct RatesInputs {
  RatesInputs(const Particles<D>& particles, const std::vector<Vector<D>>& viscous_velocity,
              const std::vector<Vector<D>>& density_gradient, const std::vector<double>& diffused_density,
              const TaitEos& tait, const MonaghanAV& artificial_viscosity)
      : P(particles),
        uv(viscous_velocity),
        grad_rho(density_gradient),
        diffused(diffused_density),
        eos(tait),
        av(artificial_viscosity) {}
  const Particles<D>& P;
  const std::vector<Vector<D>>& uv;        // velocities the viscous term sees (walls mirrored)
  const std::vector<Vector<D>>& grad_rho;  // Antuono's density gradients (empty: Molteni)
  const std::vector<double>& diffused;     // the density field the diffusion acts on
  const TaitEos& eos;
  const MonaghanAV& av;
  RateForms forms;
  double h = 0.0, inv_R = 0.0, nu = 0.0;
  double delta_h_c0 = 0.0;                                     // the diffusion's delta h c0
  Vector<D> hydrostatic_density_gradient = Vector<D>::Zero();  // Fourtakas et al. (2019): rho0 g / c0^2
  const std::vector<Vector<D>>* wall_velocity = nullptr;       // moving bodies' (others zero); null: none
  // Free-surface flags (owned and ghosts): no density diffusion out of the surface layer
  // (drains_surface_layer). Null: diffusion between every pair.
  const std::vector<double>* surface = nullptr;
};

// Whether the diffusion between fluid particles i and j would move density out of the free surface's
// layer: from a surface particle denser than its neighbour inside (`excess`: rho_j minus rho_i, both
// at i's height). The symmetric pressure force holds the surface layer above the linear hydrostatic
// density; across the cut support the diffusion drained it, and still water sank without end. Into
// the layer it still flows: a surface particle under tension is diffused up (docs/verification/
// free_surface.md, "The causes"). Decided alike from i's side and j's, so the pair stays conservative.
template <int D> inline bool drains_surface_layer(const RatesInputs<D>& in, int i, int j, double excess) {
  if (!in.surface || in.P.kind[j] != kFluid) return false;
  const bool surface_i = (*in.surface)[i] != 0.0, surface_j = (*in.surface)[j] != 0.0;
  return (surface_i && !surface_j && excess < 0.0) || (surface_j && !surface_i && excess > 0.0);
}

// Adds pair (i, j) to i's sums: pressure (corrected sums or the symmetric force) with artificial
// viscosity, viscosity (the consistent Laplacian's moments, finished after the loop, or Morris),
// continuity (corrected sums or the plain form) and delta-SPH density diffusion. Always inlined into
// the pair loop, so that the sums stay in registers: out of line it is slower than the loop body it
// replaced (docs/performance.md, "Design measurements").
template <int D> [[gnu::always_inline]] inline void add_rates_pair(const RatesInputs<D>& in, RateSums<D>& s, int i,
                                                                   int j, const PairGeometry<D>& g) {
  const Particles<D>& P = in.P;
  const Vector<D> zero = Vector<D>::Zero();
  const Vector<D> uij = P.v[i] - P.v[j];
  const double Vj = P.m[j] / P.rho[j];
  const double Pi = in.av.active() ? in.av.Pi(in.h, in.eos, P.rho[i], P.rho[j], uij, g) : 0.0;
  if (in.forms.corrected_gradient) {
    s.M += correction_moment_term(Vj, g);
    s.grad_p += difference_gradient_term(Vj, P.p[i], P.p[j], g);
  } else {
    s.acc += pressure_acceleration_pair(P.m[j], P.p[i], P.p[j], P.rho[i], P.rho[j], g);
  }
  if (Pi != 0.0) s.acc_av -= (P.m[j] * Pi) * g.gradW;
  const double F = morris_factor(g, in.h);
  if (in.forms.viscous) {
    if (in.forms.consistent_viscous) s.viscous.add(Vj, g, in.inv_R, Vector<D>(in.uv[j] - in.uv[i]));
    else
      s.acc_viscous +=
          morris_viscous_acceleration(P.m[j], P.rho[i], P.rho[j], in.nu, in.nu, F, Vector<D>(in.uv[i] - in.uv[j]));
  }
  if (in.forms.continuity) {
    // Walls count as at rest here (moving bodies aside): every wall is fixed or slides along itself
    // (the cavity lid), so no mass crosses it, and the sliding velocity must stay out of the density. Where the lid
    // ends at a fixed corner block its velocity jumps from U to 0 inside the kernel support, and the discrete
    // divergence reads that jump as a source of order U/dx, which this equation integrates in time into a compression
    // of the whole cavity (docs/verification/lid_driven_cavity.md, "Design measurements"). ISPH's pressure source can
    // keep v_w (-ppe_wall_velocity prescribed): the projection does not accumulate the source, which there raises the
    // stagnation pressure in the downstream corner and drives the vortex harder, a first-order error that on coarse
    // grids at Re 1000 cancels most of the scheme's under-resolution (docs/verification/lid_driven_cavity.md, "Why the
    // best corner depends on Re").
    const Vector<D> u_j = P.kind[j] != kWall ? Vector<D>(P.v[j])
                          : in.wall_velocity ? Vector<D>((*in.wall_velocity)[j])
                                             : Vector<D>::Zero();
    if (in.forms.corrected_continuity) s.grad_u += difference_vector_gradient_term(Vj, P.v[i], u_j, g);
    else s.drho += continuity_pair(P.rho[i], Vj, Vector<D>(P.v[i] - u_j), g);
    // Fourtakas et al. (2019): the hydrostatic density difference of the pair, (rho0 g / c0^2) . (x_j - x_i)
    // to first order in g h / c0^2, is not diffused: still water stays still.
    if (in.forms.diffuse) {
      const double rho_j = in.diffused[j] + in.hydrostatic_density_gradient.dot(g.rij);
      if (!drains_surface_layer(in, i, j, rho_j - in.diffused[i]))
        s.drho_diffusion += density_diffusion_pair(in.delta_h_c0, in.diffused[i], rho_j, Vj, F,
                                                   in.grad_rho.empty() ? zero : in.grad_rho[i],
                                                   in.grad_rho.empty() ? zero : in.grad_rho[j], g);
    }
  }
}

}  // namespace sph::wcsph
