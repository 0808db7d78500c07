#pragma once
// Free-surface particles, shared by every scheme with a free surface (ISPH's surface condition, the
// shifting of ISPH and WCSPH alike).
//
// Detection: the divergence of position, div r_i = -(1/rho_i) sum_j m_j r_ij . grad_i W_ij, equals the
// dimension D inside the fluid and drops where the support is cut by the surface (Lee et al. 2008; Lind
// et al. 2012 use div r < 1.5 in 2D). Only fluid particles are flagged. Wall particles count as
// neighbours (a fluid particle on a wall is not on the surface), so a fluid particle with no fluid
// neighbour at all (a droplet stuck in a wall corner) is flagged explicitly.
//
// Hysteresis: a particle flagged at the last step stays flagged until div r rises past a higher exit
// threshold. With a single threshold a particle whose div r hovers at it switches between the surface
// condition and an interior row from step to step; each switch is a pressure impulse, so that noise
// came per step, not per unit time.
#include <petscsys.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <vector>

#include "src/core/option_reads.hpp"
#include "src/core/options.hpp"
#include "src/neighbours/neighbourhood.hpp"
#include "src/sph/free_surface_marrone.hpp"
#include "src/sph/pair_loop.hpp"

namespace sph {

// Which particles in the hysteresis band of div r (not flagged at the last step) the umbrella scan decides
// (-free_surface_scan): none, those with a wall in their support, or all of them.
enum class BandScan { Default, None, Walls, All };
inline const char* const band_scan_names[] = {"default", "none", "walls", "all"};

template <int D> double default_free_surface_threshold() { return D == 1 ? 0.75 : D == 2 ? 1.5 : 2.4; }
// Exit threshold: 40 % of the way from the entry threshold to the interior value D (1.7 in 2D).
template <int D> double default_free_surface_exit_threshold(double threshold) {
  return threshold + 0.4 * (D - threshold);
}

template <int D>
std::vector<double> position_divergence(const Particles<D>& P, const NeighbourList<D>& nl, const Kernel<D>& K) {
  std::vector<double> div(P.n_owned, 0.0);
  for_each_pair(P, nl, K, [&](int i, int j, const PairGeometry<D>& g) { div[i] -= P.m[j] * g.rij.dot(g.gradW); });
  for (std::size_t i = 0; i < P.n_owned; ++i) div[i] /= P.rho[i];
  return div;
}

// 1 for fluid particles on the free surface, 0 otherwise (one entry per owned particle). With
// `previous` (the last step's flags, nonzero = on the surface), a flagged particle stays flagged while
// div r < exit_threshold. An unflagged particle with threshold <= div r < exit_threshold (`scan`: all
// such, or those with a wall in their support) is on the surface when nothing lies beyond it: Marrone et
// al. (2010)'s umbrella scan along -grad C (walls included). Why: where walls fill most of a support, div r
// reads a surface particle as nearly full;
// the particle at the top of a 3D tank's vertical edge has div r 2.53 (threshold 2.4), the 2D corner's
// 1.496 (threshold 1.5), and as an interior row with an empty octant its pressure rose and it sank
// (docs/verification/free_surface.md, "Surface particles in the corners").
template <int D>
std::vector<char> free_surface_particles(const Particles<D>& P, const NeighbourList<D>& nl, const Kernel<D>& K,
                                         double threshold, double exit_threshold = 0.0,
                                         const std::vector<double>* previous = nullptr, BandScan scan = BandScan::All) {
  const std::vector<double> div = position_divergence(P, nl, K);
  std::vector<char> has_fluid(P.n_owned, 0), has_wall(P.n_owned, 0);
  for_each_pair(P, nl, K, [&](int i, int j, const PairGeometry<D>&) {
    has_fluid[i] |= P.kind[j] == kFluid;
    has_wall[i] |= P.kind[j] != kFluid;
  });
  std::vector<char> surface(P.n_owned, 0), doubtful(P.n_owned, 0);
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    const bool flagged = previous && (*previous)[i] != 0.0;
    const bool stays = flagged && div[i] < exit_threshold;
    surface[i] = P.kind[i] == kFluid && (div[i] < threshold || stays || !has_fluid[i]);
    const bool scanned = scan == BandScan::All || (scan == BandScan::Walls && has_wall[i]);
    doubtful[i] = scanned && P.kind[i] == kFluid && !surface[i] && div[i] < exit_threshold;
  }
  // Most steps have no band particle to scan: the two pair loops below are skipped then, by every rank
  // together (a pair loop refreshes and checks ghosts, which is collective).
  int any = std::any_of(doubtful.begin(), doubtful.end(), [](char d) { return d != 0; });
  MPI_Allreduce(MPI_IN_PLACE, &any, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
  if (!any) return surface;
  std::vector<Vector<D>> normal(P.n_owned, Vector<D>::Zero());
  for_each_pair(P, nl, K, [&](int i, int j, const PairGeometry<D>& g) {
    if (doubtful[i]) normal[i] -= (P.m[j] / P.rho[j]) * g.gradW;
  });
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    if (!doubtful[i]) continue;
    if (normal[i].squaredNorm() > 0.0) normal[i].normalize();
    else doubtful[i] = 0;  // a symmetric support has no outside to scan: inside
  }
  const std::vector<char> covered = umbrellas_covered(P, nl, K, doubtful, normal);
  for (std::size_t i = 0; i < P.n_owned; ++i)
    if (doubtful[i] && !covered[i]) surface[i] = 1;
  return surface;
}

// 1 for owned particles with a free-surface particle among their neighbours (or on it); `surface`
// holds owned and ghost values.
template <int D> std::vector<char> near_free_surface(const Particles<D>& P, const NeighbourList<D>& nl,
                                                     const Kernel<D>& K, const std::vector<double>& surface) {
  check_ghosts(nl, surface, "the surface flags");
  std::vector<char> near(P.n_owned, 0);
  for (std::size_t i = 0; i < P.n_owned; ++i) near[i] = surface[i] != 0.0;
  for_each_pair(P, nl, K, [&](int i, int j, const PairGeometry<D>&) { near[i] |= surface[j] != 0.0; });
  return near;
}

// The owned particles' surface flags (1: on the surface) as a field with its ghosts' values, for the
// pair loops that read a neighbour's flag.
template <int D> std::vector<double> surface_flags_with_ghosts(const std::vector<char>& surface, const Particles<D>& P,
                                                               const Neighbourhood<D>& nh) {
  std::vector<double> flags(surface.begin(), surface.end());
  flags.resize(P.size(), 0.0);
  nh.halo().update(flags);
  return flags;
}

// How the surface is found (-free_surface_detection): div r below a threshold, with hysteresis (above),
// or Marrone et al. (2010)'s eigenvalue and scan (src/sph/free_surface_marrone.hpp).
enum class SurfaceDetection { DivR, Marrone };
inline const char* const surface_detection_names[] = {"div_r", "marrone"};

// Fluid particles with no fluid neighbour (droplets on their own, or stuck on a wall).
template <int D>
std::vector<char> isolated_fluid_particles(const Particles<D>& P, const NeighbourList<D>& nl, const Kernel<D>& K) {
  std::vector<char> has_fluid(P.n_owned, 0);
  for_each_pair(P, nl, K, [&](int i, int j, const PairGeometry<D>&) { has_fluid[i] |= P.kind[j] == kFluid; });
  std::vector<char> isolated(P.n_owned, 0);
  for (std::size_t i = 0; i < P.n_owned; ++i) isolated[i] = P.kind[i] == kFluid && !has_fluid[i];
  return isolated;
}

// Where shifting meets a free surface (src/sph/shifting.hpp): kind 1 on the surface (not shifted),
// 2 beside it (never outwards, along `normal`, the kernel-weighted mean of the surface
// neighbours' normals); 0 elsewhere. Owned particles.
template <int D> struct ShiftBoundary {
  std::vector<char> kind;
  std::vector<Vector<D>> normal;
};

// The free-surface model of a run: its options (-free_surface_detection, -free_surface_threshold,
// -free_surface_exit_threshold, read once for every scheme), the flags of the last step that the
// hysteresis needs (the particles' field "free_surface": carried, and written to the frames in scenes
// with a free surface) and what the schemes ask of it.
template <int D> class FreeSurface {
 public:
  void set_from_options();
  // Resolves the defaults (`scan`: the scheme's -free_surface_scan) and declares the flags' field; call
  // once the scene is known.
  void setup(Particles<D>& P, bool free_surface, BandScan scan);

  // The surface particles at the current positions; `remember` makes them the state that the next
  // call's hysteresis starts from (once a step).
  std::vector<char> detect(Particles<D>& P, const NeighbourList<D>& nl, const Kernel<D>& K, bool remember);
  // The surface and near-surface particles, and the surface's normal beside it, for shifting.
  ShiftBoundary<D> shift_boundary(const Particles<D>& P, Neighbourhood<D>& nh, const Kernel<D>& K,
                                  const std::vector<char>& surface) const;

  nlohmann::json describe() const {
    if (detection_ == SurfaceDetection::Marrone)
      return {{"detection", "Marrone et al. 2010"},
              {"surface_eigenvalue", marrone::surface_eigenvalue},
              {"interior_eigenvalue", marrone::interior_eigenvalue}};
    return {{"detection", "div r"},
            {"threshold_div_r", threshold_},
            {"exit_threshold_div_r", exit_threshold_},
            {"band_scan", band_scan_names[static_cast<int>(scan_)]}};
  }

 private:
  SurfaceDetection detection_ = SurfaceDetection::DivR;
  PetscReal threshold_ = 0.0;       // 0: the dimension's default
  PetscReal exit_threshold_ = 0.0;  // 0: default_free_surface_exit_threshold
  BandScan scan_ = BandScan::Default;
  FieldId<double> state_;  // the last step's flags (1: on the surface)
};

namespace detail {
inline PetscErrorCode read_free_surface_options(PetscInt* detection, PetscReal* threshold, PetscReal* exit_threshold,
                                                PetscInt* scan) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(PETSC_COMM_WORLD, nullptr, "Free surface (scenes with one; every scheme)", "FreeSurface");
  PetscCall(option_choice(
      PetscOptionsObject, "-free_surface_detection",
      "Free-surface particles: div_r (div r below -free_surface_threshold, with hysteresis; "
      "Lind et al. 2012) or marrone (the moment matrix's smallest eigenvalue, then a scan "
      "beyond the particle; Marrone et al. 2010; ISPH fails three of the violent free-surface scenes with "
      "it: docs/verification/free_surface.md)",
      surface_detection_names, 2, surface_detection_names[*detection], detection, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-free_surface_threshold",
                        "Free-surface particles: div r below this (0: 1.5 in 2D, 2.4 in 3D; Lind et al. 2012)",
                        *threshold, threshold, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-free_surface_exit_threshold",
                        "A surface particle stays on the surface until div r exceeds this (0: the threshold plus "
                        "0.4 of its distance to the dimension, 1.7 in 2D)",
                        *exit_threshold, exit_threshold, nullptr, OptionLevel::expert));
  PetscCall(option_choice(PetscOptionsObject, "-free_surface_scan",
                          "Particles with div r between the two thresholds, not on the surface at the last step, "
                          "that join it when nothing lies beyond them (Marrone's umbrella scan): none, walls (those "
                          "with a wall in their support: a tank's corners), all (default: all for ISPH, walls for "
                          "WCSPH; docs/verification/free_surface.md, \"Surface particles in the corners\")",
                          band_scan_names, 4, band_scan_names[*scan], scan, nullptr, OptionLevel::expert));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}
}  // namespace detail

template <int D> void FreeSurface<D>::set_from_options() {
  PetscInt detection = static_cast<PetscInt>(detection_), scan = static_cast<PetscInt>(scan_);
  SPH_PETSC(detail::read_free_surface_options(&detection, &threshold_, &exit_threshold_, &scan));
  detection_ = static_cast<SurfaceDetection>(detection);
  scan_ = static_cast<BandScan>(scan);
  require(threshold_ >= 0 && threshold_ < D, "-free_surface_threshold", "in [0, dimension)", threshold_);
  require(exit_threshold_ >= 0 && exit_threshold_ < D, "-free_surface_exit_threshold", "in [0, dimension)",
          exit_threshold_);
}

template <int D> void FreeSurface<D>::setup(Particles<D>& P, bool free_surface, BandScan scan) {
  state_ = P.fields.declare_scalar("free_surface", kCarried | (free_surface ? kWritten : 0u), P.size());
  if (scan_ == BandScan::Default) scan_ = scan;
  if (threshold_ <= 0) threshold_ = default_free_surface_threshold<D>();
  if (exit_threshold_ <= 0) exit_threshold_ = default_free_surface_exit_threshold<D>(threshold_);
  require(exit_threshold_ >= threshold_, "-free_surface_exit_threshold", "at least -free_surface_threshold",
          exit_threshold_);
}

template <int D> std::vector<char> FreeSurface<D>::detect(Particles<D>& P, const NeighbourList<D>& nl,
                                                          const Kernel<D>& K, bool remember) {
  std::vector<double>& state = P.fields[state_];
  std::vector<char> surface = detection_ == SurfaceDetection::Marrone
                                  ? marrone_surface_particles(P, nl, K, &state)
                                  : free_surface_particles(P, nl, K, threshold_, exit_threshold_, &state, scan_);
  if (remember) std::copy(surface.begin(), surface.end(), state.begin());  // owned rows
  return surface;
}

template <int D> ShiftBoundary<D> FreeSurface<D>::shift_boundary(const Particles<D>& P, Neighbourhood<D>& nh,
                                                                 const Kernel<D>& K,
                                                                 const std::vector<char>& surface) const {
  const NeighbourList<D>& nl = nh.list();
  const std::vector<double> flags = surface_flags_with_ghosts(surface, P, nh);
  // The surface particles' own normals, -grad C / |grad C| (walls included), for their neighbours.
  std::vector<Vector<D>> own = sum_over_pairs(
      P, nl, K, Vector<D>(Vector<D>::Zero()),
      [&](Vector<D>& s, int i, int j, const PairGeometry<D>& g) {
        if (surface[i]) s -= (P.m[j] / P.rho[j]) * g.gradW;
      },
      Rows::Fluid);
  for (auto& n : own)
    if (n.squaredNorm() > 0.0) n.normalize();
  own.resize(P.size(), Vector<D>::Zero());
  nh.halo().update(own);
  ShiftBoundary<D> b;
  b.kind.assign(P.n_owned, 0);
  b.normal = sum_over_pairs(
      P, nl, K, Vector<D>(Vector<D>::Zero()),
      [&](Vector<D>& s, int, int j, const PairGeometry<D>& g) {
        if (flags[j] != 0.0) s += g.W * own[j];
      },
      Rows::Fluid);
  const std::vector<char> near = near_free_surface(P, nl, K, flags);
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    b.kind[i] = surface[i] ? 1 : near[i] ? 2 : 0;
    if (b.normal[i].squaredNorm() > 0.0) b.normal[i].normalize();
  }
  return b;
}

}  // namespace sph
