#pragma once
// Particle shifting (Lind, Xu, Stansby & Rogers 2012; Skillen et al. 2013): particles drift down the
// gradient of particle concentration, dr_i = -D grad C_i, which keeps the distribution near-uniform
// (avoiding the clustering and voids that ruin Lagrangian SPH), and fields are Taylor-corrected to the
// shifted positions.
//
// D = A h U dt (Lind et al. 2012; U the largest particle speed, largest_speed): a shift per unit time, so that
// the total shift over a time interval does not depend on how many steps cut it: a shift per step
// (A h^2) made the error grow as dt fell. The explicit update is stable for D <= 0.5 h^2 per step: D is
// capped there, so shifting sets no time-step limit (docs/verification/speed_against_error.md, "Larger steps").
//   grad C_i = sum_j V_j [1 + R (W_ij / W(dx))^n] grad_i W_ij  (R = 0.2, n = 4: the tensile-instability
//   term of Monaghan 2000 that Lind et al. add to stop pairing).
#include <algorithm>
#include <array>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <vector>

#include "src/core/integer_power.hpp"
#include "src/core/log_events.hpp"
#include "src/core/option_reads.hpp"
#include "src/core/options.hpp"
#include "src/neighbours/neighbourhood.hpp"
#include "src/sph/free_surface.hpp"
#include "src/sph/kernel_average.hpp"
#include "src/sph/operators.hpp"

namespace sph {

// How fast particles are shifted (-shift_rate). D = A h U dt (speed, Lind et al. 2012) restores a
// particle-scale disorder at the rate A U / h, which grows as h falls, while the flow disorders
// particles at its strain rate, which does not. D = A h^2 |S_i| dt (strain; S_i the particle's
// strain-rate tensor, |.| the Frobenius norm) restores at a rate proportional to the local strain rate
// at every resolution, and shifts nothing where the flow does not deform (a rigid rotation, a fluid at
// rest). speed stays the default: strain has less decay bias but lets the start's square lattice
// rearrange with a first-order error burst that speed suppresses, and neither is second order in h yet
// (docs/verification/taylor_green.md, "What limits ISPH's order" and "Design measurements").
enum class ShiftRate { Speed, Strain };
inline const char* const shift_rate_names[] = {"speed", "strain"};
inline const char* const shift_rate_help =
    "Shift diffusivity: speed (D = A h U dt, U the largest particle speed, Lind et al. 2012) or strain (D = A h^2 |S| "
    "dt, S the local strain rate: no shift where the flow does not deform)";
// Which part of grad C particles shift along (-shift_scales). The kernel sum C is not 1 on a uniform
// but anisotropic arrangement, and the flow's strain makes such arrangements systematically: C then has
// a smooth, resolved-scale part of O(1) in h, and shifting along its gradient (D = A h U dt) moves
// mass at the flow's scale by O(h), which fixed particle volumes do not account for: a first-order
// energy input that keeps ISPH's order under 2. particle: shift along grad C minus its kernel (Shepard)
// average over the fluid, the particle-scale part that disorder makes and shifting is for; the resolved
// part left is O(h^2) smaller, and its energy input third order. Not the default yet: it restores
// disorder a few particles wide more weakly, and the start lattice's rearrangement on coarse grids grows
// a little (docs/verification/taylor_green.md, "What limits ISPH's order" and "Design measurements").
enum class ShiftScales { All, Particle };
inline const char* const shift_scales_names[] = {"all", "particle"};
inline const char* const shift_scales_help =
    "What shifting removes: all (the whole grad C, Lind et al. 2012) or particle (grad C minus its kernel average: "
    "particle-scale disorder only, not the resolved-scale part that the flow's strain gives C)";
inline const char* const shift_coefficient_help =
    "Shifting coefficient A (-1: 2 with -shift_rate speed, 5 with strain; either way D is at most 0.5 h^2, the "
    "explicit shift's stability)";

// The largest particle speed over all ranks, moving walls included (a lid sets its flow's speed): the
// speed that -shift_rate speed shifts at. With the case's reference speed instead, a fluid at rest is
// shifted too, and the square lattice it starts on (a saddle of the shift's potential, which favours a
// hexagonal one) rearranges (docs/verification/free_surface.md, "Design measurements").
template <int D> double largest_speed(const Particles<D>& P) {
  double u2 = 0.0;
  for (std::size_t i = 0; i < P.n_owned; ++i) u2 = std::max(u2, P.v[i].squaredNorm());
  MPI_Allreduce(MPI_IN_PLACE, &u2, 1, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
  return std::sqrt(u2);
}

// The shifting model of a run, shared by ISPH and WCSPH: its options (-shifting, -shift_rate,
// -shift_coefficient, -shift_scales) are one block, read and checked once whichever scheme runs.
struct LindShifting {
  bool enabled = true;  // -shifting
  ShiftRate rate = ShiftRate::Speed;
  ShiftScales scales = ShiftScales::All;
  double A = -1.0;                              // -1: the rate's default (default_coefficient)
  double R = 0.2;                               // tensile-correction strength
  int n = 4;                                    // tensile-correction exponent
  static constexpr double max_D_over_h2 = 0.5;  // stability of the explicit shift

  void set_from_options();
  static double default_coefficient(ShiftRate r) { return r == ShiftRate::Speed ? 2.0 : 5.0; }
  double coefficient_A() const { return A >= 0.0 ? A : default_coefficient(rate); }
  // D of a particle: speed: A h U dt; strain: A h^2 |S| dt; either at most max_D_over_h2 h^2, the
  // explicit shift's stability. Capped rather than bounding the step, so shifting sets no step limit.
  double coefficient(double h, double U, double dt, double strain_rate = 0.0) const {
    const double D =
        rate == ShiftRate::Speed ? coefficient_A() * h * U * dt : coefficient_A() * h * h * strain_rate * dt;
    return std::min(D, max_D_over_h2 * h * h);
  }
  nlohmann::json describe() const {
    return {{"model", "LindShifting"},
            {"rate", shift_rate_names[static_cast<int>(rate)]},
            {"scales", shift_scales_names[static_cast<int>(scales)]},
            {"D", rate == ShiftRate::Speed ? "min(A h U dt, 0.5 h^2)" : "min(A h^2 |S| dt, 0.5 h^2)"},
            {"A", coefficient_A()},
            {"R", R},
            {"n", n}};
  }
};

namespace detail {
inline PetscErrorCode read_shifting_options(PetscBool* enabled, PetscInt* rate, PetscReal* A, PetscInt* scales) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(PETSC_COMM_WORLD, nullptr, "Particle shifting (ISPH and WCSPH)", "Shifting");
  PetscCall(option_bool(PetscOptionsObject, "-shifting",
                        "Particle shifting (Lind et al. 2012), the particles' fields Taylor-corrected to their "
                        "new positions",
                        *enabled, enabled, nullptr));
  PetscCall(option_choice(PetscOptionsObject, "-shift_rate", shift_rate_help, shift_rate_names, 2,
                          shift_rate_names[*rate], rate, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-shift_coefficient", shift_coefficient_help, *A, A, nullptr,
                        OptionLevel::expert));
  PetscCall(option_choice(PetscOptionsObject, "-shift_scales", shift_scales_help, shift_scales_names, 2,
                          shift_scales_names[*scales], scales, nullptr, OptionLevel::expert));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}
}  // namespace detail

inline void LindShifting::set_from_options() {
  PetscBool on = enabled ? PETSC_TRUE : PETSC_FALSE;
  PetscInt r = static_cast<PetscInt>(rate), s = static_cast<PetscInt>(scales);
  PetscReal a = A;
  SPH_PETSC(detail::read_shifting_options(&on, &r, &a, &s));
  require(a >= 0 || a == -1, "-shift_coefficient", "non-negative (or -1: the shift rate's default)", a);
  enabled = on, rate = static_cast<ShiftRate>(r), A = a, scales = static_cast<ShiftScales>(s);
}

// g_i minus its kernel average (src/sph/kernel_average.hpp): the part of grad C that varies on the
// particle scale. Only where the kernel support is all fluid: next to a wall or a free surface the
// resolved part of grad C is the boundary's own signal, which keeps particles off walls, and g_i is kept
// whole (docs/verification/lid_driven_cavity.md, "Design measurements").
template <int D> void remove_kernel_average(const Particles<D>& P, Neighbourhood<D>& nh, const Kernel<D>& K,
                                            std::vector<Vector<D>>& g, const std::vector<char>* surface) {
  const KernelAverage<Vector<D>> average = kernel_average_in_fluid(P, nh, K, g, surface);
  for (std::size_t i = 0; i < P.n_owned; ++i)
    if (average.interior[i]) g[i] -= average.average[i];
}

// Shifts the owned particles by -D grad C, D = model.coefficient(h, U, dt) (with a free surface, as
// `surface` says: not on it, and beside it never outwards) and Taylor-corrects the velocity,
// u + (dr . grad) u with the corrected gradient, and the listed scalar fields likewise. Positions must
// be current in `nh`.
//
// One pair loop gathers all of it: grad C, the moment matrix of the kernel-gradient correction and the
// uncorrected gradients of u and of the scalars. As separate operators (correction_matrices,
// vector_gradient_corrected, gradient_corrected) these were one loop each, and traversing the pairs,
// not the arithmetic, is the cost: the fused loop gives each sum bitwise the same terms in the same
// order (tests/test_shifting.cpp), in less time (docs/performance.md, "Design measurements").
template <int D> void shift_particles(Particles<D>& P, Neighbourhood<D>& nh, const Kernel<D>& K,
                                      const LindShifting& model, double dx, double U, double dt,
                                      const std::vector<std::vector<double>*>& scalars = {},
                                      const ShiftBoundary<D>* surface = nullptr) {
  const LogEventScope log_shifting(LogEvent::Shifting);
  const NeighbourList<D>& nl = nh.list();
  const std::size_t n = P.n_owned;
  std::vector<Vector<D>> dr(n, Vector<D>::Zero());
  std::vector<Tensor<D>> L(n, Tensor<D>::Zero()), grad_u(n, Tensor<D>::Zero());
  std::vector<std::vector<Vector<D>>> grad_f(scalars.size(), std::vector<Vector<D>>(n, Vector<D>::Zero()));
  const double W_dx = K.W(dx);
  // The sums of one particle live in locals while its pairs are visited (registers, not a store to
  // the arrays at every pair); same terms in the same order.
  constexpr std::size_t max_scalars = 4;
  if (scalars.size() > max_scalars) throw std::logic_error("shift_particles: more than 4 scalar fields");
  const std::size_t ns = scalars.size();
  std::array<const double*, max_scalars> f{};
  for (std::size_t k = 0; k < ns; ++k) f[k] = scalars[k]->data(), check_ghosts(nl, *scalars[k], "a shifted field");
  for_each_particle_pairs(
      P, nl, K,
      [&](std::size_t i, auto&& visit_pairs) {
        Vector<D> dr_i = Vector<D>::Zero();
        Tensor<D> L_i = Tensor<D>::Zero(), grad_u_i = Tensor<D>::Zero();
        std::array<Vector<D>, max_scalars> grad_f_i;
        for (std::size_t k = 0; k < ns; ++k) grad_f_i[k].setZero();
        visit_pairs([&](int, int j, const PairGeometry<D>& g) {
          const double Vj = P.m[j] / P.rho[j];
          dr_i += (Vj * (1.0 + model.R * integer_power(g.W / W_dx, model.n))) * g.gradW;
          L_i += correction_moment_term(Vj, g);
          grad_u_i += difference_vector_gradient_term(Vj, P.v[i], P.v[j], g);
          for (std::size_t k = 0; k < ns; ++k) grad_f_i[k] += difference_gradient_term(Vj, f[k][i], f[k][j], g);
        });
        dr[i] = dr_i, L[i] = L_i, grad_u[i] = grad_u_i;
        for (std::size_t k = 0; k < ns; ++k) grad_f[k][i] = grad_f_i[k];
      },
      Rows::Fluid);  // walls do not shift
  std::vector<char> on_surface;
  if (surface)
    for (std::size_t i = 0; i < n; ++i) on_surface.push_back(surface->kind[i] == 1);
  if (model.scales == ShiftScales::Particle) remove_kernel_average(P, nh, K, dr, surface ? &on_surface : nullptr);
  const double Dcoef = model.coefficient(K.h(), U, dt);
  for (std::size_t i = 0; i < n; ++i) {
    // A sheet's or a drop's corrected velocity gradient amplifies its noise: uncorrected there
    // (docs/verification/free_surface.md).
    L[i] = moments_resolve(L[i]) ? correction_from_moments(L[i]) : Tensor<D>(Tensor<D>::Identity());
    if (model.rate == ShiftRate::Speed) {
      dr[i] *= -Dcoef;
    } else {
      const Tensor<D> G = L[i] * grad_u[i];
      dr[i] *= -model.coefficient(K.h(), U, dt, (0.5 * (G + G.transpose())).norm());
    }
  }
  // The surface particles stay put. Along the surface (Lind et al. 2012's tangential shift) they
  // would leave the drop's tips, where the flow crowds them, and a WCSPH splash blew up with it
  // (docs/verification/free_surface.md, "Elliptical drop"). Beside the surface never outwards: there
  // the cut support's grad C points into the fluid as well, and shifting would move the layer below the
  // surface into it, lifting a fluid at rest (docs/verification/free_surface.md, "Design measurements").
  if (surface)
    for (std::size_t i = 0; i < n; ++i) {
      if (surface->kind[i] == 1) dr[i].setZero();
      const double outward = surface->normal[i].dot(dr[i]);
      if (surface->kind[i] == 2 && outward > 0.0) dr[i] -= outward * surface->normal[i];
    }
  // Only fluid particles move; walls keep their place.
  for (std::size_t k = 0; k < scalars.size(); ++k)
    for (std::size_t i = 0; i < n; ++i)
      if (P.kind[i] == kFluid) (*scalars[k])[i] += Vector<D>(L[i] * grad_f[k][i]).dot(dr[i]);
  for (std::size_t i = 0; i < n; ++i) {
    if (P.kind[i] != kFluid) continue;
    P.x[i] += dr[i];
    P.v[i] += Tensor<D>(L[i] * grad_u[i]).transpose() * dr[i];
  }
  // The ghosts follow what the shift wrote (the lists stay those of the last update).
  nh.halo().update_positions(P.x);
  nh.halo().update(P.v);
  for (std::vector<double>* field : scalars) nh.halo().update(*field);
}

}  // namespace sph
