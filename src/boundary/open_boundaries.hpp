#pragma once
// Open boundaries: inlets and outlets on sides of the box, each a buffer of particles as deep as the
// kernel's support beyond the side (Lastiwka, Basa & Quinlan 2009; Tafuni et al. 2018). The buffer
// completes the fluid's kernel supports there, as wall layers do at a wall:
// - an inlet's particles (kind kInlet) move with the prescribed velocity, and their pressure is
//   extrapolated from the fluid as a wall's is (Adami et al. 2012: a zero normal gradient but for the
//   body force's head). One that crosses into the box becomes fluid, and a new inlet particle takes
//   its place one buffer depth behind it, so the buffer's lattice stays whole;
// - an outlet's particles (kind kOutlet) drift with the fluid's velocity carried outwards (a zero normal
//   gradient). Their pressure is the outlet's (OutletPressure::Fixed: a Dirichlet condition for ISPH's
//   pressure system, the density of that pressure for WCSPH), or, for WCSPH, one that lets sound out
//   (OutletPressure::Transmissive, below). One that comes back into the box is fluid again; one that
//   leaves the buffer's far end leaves the run, counted as outflow, never as lost fluid.
// The particles' count changes during a run: new particles take ids from next_id, which the
// checkpoint keeps (docs/verification/open_boundaries.md).
#include <mpi.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "src/core/expression.hpp"
#include "src/neighbours/neighbour_list.hpp"
#include "src/particles/global_indices.hpp"
#include "src/particles/particles.hpp"
#include "src/particles/remove_particles.hpp"
#include "src/sph/pair_loop.hpp"

namespace sph {

// The velocity an inlet prescribes: uniform, the parabolic profile of a channel (2D) or a
// rectangular duct (3D, the product of the two parabolas) across the inlet's section, or the user's
// expressions of the place (x, y and, in 3D, z), one a component; each times a ramp from rest, (1 - cos(pi t / T)) / 2
// up to t = T (none for T = 0), and times a speed table's factor at t (linear between its rows, held
// before the first and after the last; none without a table).
template <int D> struct InletVelocity {
  enum class Profile { Uniform, Parabolic, Expressions };
  Profile profile = Profile::Uniform;
  Vector<D> velocity = Vector<D>::Zero();     // Uniform
  double peak = 0.0;                          // Parabolic: the speed on the section's centre, along the inward normal
  std::vector<Expression> expressions;        // Expressions: one a component
  double expressions_top = 0.0;               // Expressions: their largest speed across the section
  double ramp = 0.0;                          // T
  std::vector<double> table_t, table_factor;  // the speed table: t increasing, factors >= 0

  double factor(double t) const { return ramp_factor(t) * table_value(t); }
  // The largest factor over the run (the inlet's top speed per unit of its velocity).
  double top_factor() const {
    return table_factor.empty() ? 1.0 : *std::max_element(table_factor.begin(), table_factor.end());
  }
  // The inlet's largest speed over the run.
  double top_speed() const {
    const double full = profile == Profile::Parabolic     ? peak
                        : profile == Profile::Expressions ? expressions_top
                                                          : velocity.norm();
    return top_factor() * full;
  }

 private:
  double ramp_factor(double t) const {
    if (ramp <= 0.0 || t >= ramp) return 1.0;
    return 0.5 * (1.0 - std::cos(M_PI * std::max(t, 0.0) / ramp));
  }
  double table_value(double t) const {
    if (table_t.empty()) return 1.0;
    if (t <= table_t.front()) return table_factor.front();
    if (t >= table_t.back()) return table_factor.back();
    const std::size_t k =
        static_cast<std::size_t>(std::upper_bound(table_t.begin(), table_t.end(), t) - table_t.begin());
    const double w = (t - table_t[k - 1]) / (table_t[k] - table_t[k - 1]);
    return (1.0 - w) * table_factor[k - 1] + w * table_factor[k];
  }
};

template <int D> struct OpenBoundary {
  enum class Type { Inlet, Outlet };
  Type type = Type::Inlet;
  int axis = 0;        // the side's axis
  int side = -1;       // -1: the box's low side, +1: its high side (the outward normal is side e_axis)
  double plane = 0.0;  // where the box's side lies along the axis: the buffer begins there
  double depth = 0.0;  // the buffer's depth beyond the plane
  Vector<D> section_lo = Vector<D>::Zero(), section_hi = Vector<D>::Zero();  // the section's extent (other axes)
  InletVelocity<D> inflow;                                                   // Inlet
  double pressure = 0.0;                                                     // Outlet (at its level, if it keeps one)
  // An open channel's outlet keeps a water level: below it the pressure is hydrostatic, p + rho0 |g|
  // (level - height), the height measured along -g; above it, p. The fluid's surface at the outlet
  // settles where this pressure holds it, as a weir or a downstream reservoir would.
  bool keeps_level = false;
  double level = 0.0;
  double rho0 = 1.0;
  Vector<D> gravity = Vector<D>::Zero();

  int kind() const { return type == Type::Inlet ? kInlet : kOutlet; }
  // How far x lies beyond the plane, outwards (negative inside the box).
  double beyond(const Vector<D>& x) const { return side * (x[axis] - plane); }
  // Whether x lies across the boundary's section (its extent along the other axes).
  bool in_section(const Vector<D>& x) const {
    for (int a = 0; a < D; ++a)
      if (a != axis && (x[a] < section_lo[a] || x[a] > section_hi[a])) return false;
    return true;
  }
  // An outlet's pressure at x.
  double pressure_at(const Vector<D>& x) const {
    const double g = gravity.norm();
    if (!keeps_level || g == 0.0) return pressure;
    return pressure + rho0 * g * std::max(level + gravity.dot(x) / g, 0.0);
  }
  // A level-keeping outlet's section below its level (2D: the depth; 3D: the area), gravity along an
  // axis across it.
  double section_below_level() const {
    double area = 1.0;
    for (int a = 0; a < D; ++a) {
      if (a == axis) continue;
      if (gravity[a] == 0.0) {
        area *= section_hi[a] - section_lo[a];
        continue;
      }
      const double up = gravity[a] < 0.0 ? 1.0 : -1.0, bottom = std::min(up * section_lo[a], up * section_hi[a]);
      area *= std::max(level - bottom, 0.0);
    }
    return area;
  }
  Vector<D> inward() const {
    Vector<D> n = Vector<D>::Zero();
    n[axis] = -side;
    return n;
  }
  Vector<D> velocity_at(const Vector<D>& x, double t) const {
    const double ramp = inflow.factor(t);
    if (inflow.profile == InletVelocity<D>::Profile::Uniform) return ramp * inflow.velocity;
    if (inflow.profile == InletVelocity<D>::Profile::Expressions) {
      double c[3] = {0.0, 0.0, 0.0};
      for (int a = 0; a < D; ++a) c[a] = x[a];
      Vector<D> v;
      for (int a = 0; a < D; ++a) v[a] = inflow.expressions[static_cast<std::size_t>(a)](c[0], c[1], c[2], t);
      return ramp * v;
    }
    double shape = 1.0;
    for (int a = 0; a < D; ++a) {
      if (a == axis) continue;
      const double w = section_hi[a] - section_lo[a], s = std::clamp(x[a] - section_lo[a], 0.0, w);
      shape *= 4.0 * s * (w - s) / (w * w);
    }
    return (ramp * inflow.peak * shape) * inward();
  }
};

// What crossed the open boundaries' planes so far (all ranks): particles and mass into the box through
// inlets, and out of it through outlets (less what came back), so that the fluid's mass is its start's
// plus in minus out.
struct OpenBoundaryFlux {
  long long in_count = 0, out_count = 0;
  double in_mass = 0.0, out_mass = 0.0;
};

// How an outlet's particles get their pressure. A fixed pressure reflects a sound wave back into the
// box with its sign turned (and a zero gradient, with it unchanged), so in a weakly compressible fluid
// the start's pressure wave rings between an inlet and an outlet. A transmissive outlet keeps the
// incoming characteristic's amplitude at its place zero but for a slow relaxation of the pressure to
// the outlet's (Rudy & Strikwerda 1980; Poinsot & Lele 1992, eq. 40, Mach number neglected):
//   dp/dt - rho0 c0 dU/dt = -K (p - p_out),   K = sigma c0 / L,
// U the outward velocity across the outlet's section, averaged over a slab of a support's half-width
// about its plane (plane waves, the modes that ring along a channel, leave; waves across it do not),
// and L the box's length along the outlet's axis. An outgoing plane wave (p' = rho0 c0 U') passes, and
// the mean level settles on p_out over 1/K. Each outlet particle integrates it along its path; one that
// has just left the fluid takes the pressure of the outlet particles around it, which hold the
// condition's memory at that place, instead of its own.
enum class OutletPressure { Fixed, Transmissive };

template <int D> class OpenBoundaries {
 public:
  OpenBoundaries() = default;
  explicit OpenBoundaries(std::vector<OpenBoundary<D>> b) : b_(std::move(b)) {}

  OutletPressure outlet_pressure() const { return outlet_pressure_; }
  // Transmissive outlets, for a fluid of acoustic impedance rho0 c0: declares the outlet particles' flag
  // "just left the fluid" (1).
  void use_transmissive_outlets(Particles<D>& P, double impedance) {
    outlet_pressure_ = OutletPressure::Transmissive, impedance_ = impedance;
    entered_ = P.fields.declare_scalar("outlet_entered", kCarried, P.size());
  }

  bool any() const { return !b_.empty(); }
  const std::vector<OpenBoundary<D>>& boundaries() const { return b_; }
  bool has_outlet() const {
    return std::any_of(b_.begin(), b_.end(), [](const auto& b) { return b.type == OpenBoundary<D>::Type::Outlet; });
  }

  // The boundary a buffer particle belongs to: the one of its kind whose buffer it lies in, or the
  // nearest of its kind.
  const OpenBoundary<D>* boundary_of(const Particles<D>& P, std::size_t i) const {
    const OpenBoundary<D>* best = nullptr;
    double nearest = 0.0;
    for (const OpenBoundary<D>& b : b_) {
      if (b.kind() != P.kind[i]) continue;
      const double d = std::abs(b.beyond(P.x[i]) - 0.5 * b.depth);
      if (!best || d < nearest) best = &b, nearest = d;
    }
    return best;
  }

  // Marks the owned outlet particles in `rows` (Dirichlet rows of a pressure system; empty: made, all
  // zero). Returns whether any boundary is an outlet.
  bool mark_outlets(const Particles<D>& P, std::vector<char>& rows) const {
    if (!has_outlet()) return false;
    rows.resize(P.n_owned, 0);
    for (std::size_t i = 0; i < P.n_owned; ++i) rows[i] |= P.kind[i] == kOutlet;
    return true;
  }

  // Fixed outlets: each outlet particle's pressure where it is now (a level-keeping outlet's varies
  // with depth as the particle drifts), and that pressure's density.
  template <class DensityOf> void hold_outlet_pressure(Particles<D>& P, DensityOf&& density_of) const {
    if (!has_outlet() || outlet_pressure_ != OutletPressure::Fixed) return;
    for (std::size_t i = 0; i < P.n_owned; ++i)
      if (P.kind[i] == kOutlet)
        if (const OpenBoundary<D>* b = boundary_of(P, i))
          P.p[i] = b->pressure_at(P.x[i]), P.rho[i] = density_of(P.p[i]);
    P.written(P.p), P.written(P.rho);
  }

  // The inlets' velocity at time t on their owned particles.
  void prescribe(Particles<D>& P, double t) const {
    for (std::size_t i = 0; i < P.n_owned; ++i)
      if (P.kind[i] == kInlet)
        if (const OpenBoundary<D>* b = boundary_of(P, i)) P.v[i] = b->velocity_at(P.x[i], t);
  }

  // Outlet particles take the kernel-weighted mean velocity of their fluid and outlet neighbours nearer
  // the box (upwind: nothing comes back from deeper in the buffer): a zero normal gradient, carried a
  // support outwards a step, so that particles placed in the buffer at rest, or that left while the flow
  // was slower, do not block the outlet. A neighbour's weight grows from zero as it lies nearer, over
  // h / 2: a particle beside it in the same lattice column, its distance from the plane equal but for
  // round-off, must not count on one run and not on another (docs/verification/open_boundaries.md).
  // Positions and velocities current on the ghosts; the caller
  // refreshes the ghosts' velocities after.
  void extrapolate_outlet_velocity(Particles<D>& P, const NeighbourList<D>& nl, const Kernel<D>& K) const {
    if (!has_outlet()) return;
    struct Mean {
      Vector<D> sum = Vector<D>::Zero();
      double weight = 0.0;
    };
    std::vector<const OpenBoundary<D>*> of(P.n_owned, nullptr);
    for (std::size_t i = 0; i < P.n_owned; ++i)
      if (P.kind[i] == kOutlet) of[i] = boundary_of(P, i);
    const double ramp = 0.5 * K.h();
    const std::vector<Mean> mean =
        sum_over_pairs(P, nl, K, Mean{}, [&](Mean& m, int i, int j, const PairGeometry<D>& g) {
          const OpenBoundary<D>* b = of[i];
          if (!b || (P.kind[j] != kFluid && P.kind[j] != kOutlet)) return;
          const double nearer = std::min((b->beyond(P.x[i]) - b->beyond(P.x[j])) / ramp, 1.0);
          if (nearer <= 0.0) return;
          m.sum += (nearer * g.W) * P.v[j], m.weight += nearer * g.W;
        });
    for (std::size_t i = 0; i < P.n_owned; ++i)
      if (P.kind[i] == kOutlet && mean[i].weight > 0.0) P.v[i] = mean[i].sum / mean[i].weight;
    keep_levels(P, K.support_radius());
  }

  // A level-keeping outlet lets out what keeps its level: its particles' outward velocity, carried from
  // the fluid, times the fluid's wetted section beside the plane over the section below the level. Fluid
  // shallower than the level then leaves slower than it comes and rises, deeper fluid falls; at the level
  // the factor is 1, the zero-gradient outlet. Carried as it is, the outflow follows whatever the fluid
  // brings, and the level drifts with it (docs/verification/open_boundaries.md, the bump channel).
  // Collective.
  void keep_levels(Particles<D>& P, double slab) const {
    if (std::none_of(b_.begin(), b_.end(), [](const auto& b) { return b.keeps_level; })) return;
    const std::vector<double> wetted = wetted_sections(P, slab);
    for (std::size_t i = 0; i < P.n_owned; ++i) {
      if (P.kind[i] != kOutlet) continue;
      const OpenBoundary<D>* b = boundary_of(P, i);
      if (!b || !b->keeps_level) continue;
      const double target = b->section_below_level();
      if (target <= 0.0) continue;
      const double factor = wetted[static_cast<std::size_t>(b - b_.data())] / target;
      const Vector<D> n = -b->inward();
      P.v[i] += ((factor - 1.0) * P.v[i].dot(n)) * n;
    }
  }

  // Transmissive outlets: on the outlet particles that just left the fluid, the mean pressure of the
  // others around them; on every outlet particle, impedance times the change of its outlet's mean
  // outward velocity since the last call (none the first time, or if it did not change). Positions,
  // velocities, pressures and flags current on the ghosts. Returns whether it wrote any pressure.
  // Collective.
  bool transmit_outlet_pressure(Particles<D>& P, const NeighbourList<D>& nl, const Kernel<D>& K) {
    if (!has_outlet() || outlet_pressure_ != OutletPressure::Transmissive) return false;
    std::vector<double>& entered = P.fields[entered_];
    struct Mean {
      double sum = 0.0, weight = 0.0;
    };
    // The pair loop only on a step after which some particle entered (on any rank): most steps none did.
    int any_entered = std::any_of(entered.begin(), entered.begin() + P.n_owned, [](double e) { return e != 0.0; });
    MPI_Allreduce(MPI_IN_PLACE, &any_entered, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
    std::vector<Mean> around;
    if (any_entered)
      around = sum_over_pairs(P, nl, K, Mean{}, [&](Mean& m, int i, int j, const PairGeometry<D>& g) {
        if (P.kind[i] != kOutlet || entered[i] == 0.0 || P.kind[j] != kOutlet || entered[j] != 0.0) return;
        m.sum += g.W * P.p[j], m.weight += g.W;
      });
    const std::vector<double> outward = mean_outward_velocities(P, K.support_radius());
    if (last_outward_.empty()) last_outward_ = outward;
    for (std::size_t i = 0; i < P.n_owned; ++i) {
      if (P.kind[i] != kOutlet) continue;
      if (entered[i] != 0.0 && around[i].weight > 0.0) P.p[i] = around[i].sum / around[i].weight;
      entered[i] = 0.0;
      if (const OpenBoundary<D>* b = boundary_of(P, i)) {
        const std::size_t k = static_cast<std::size_t>(b - b_.data());
        P.p[i] += impedance_ * (outward[k] - last_outward_[k]);
      }
    }
    last_outward_ = outward;
    P.written(entered);
    return true;
  }

  // Transmissive outlets: the relaxation of their pressure to the outlet's over a step, K = sigma c0 / L.
  void relax_outlet_pressure(Particles<D>& P, double dt, double sigma_c0, const Vector<D>& box_length) const {
    if (!has_outlet() || outlet_pressure_ != OutletPressure::Transmissive) return;
    for (std::size_t i = 0; i < P.n_owned; ++i)
      if (P.kind[i] == kOutlet)
        if (const OpenBoundary<D>* b = boundary_of(P, i))
          P.p[i] -= std::min(1.0, sigma_c0 / box_length[b->axis] * dt) * (P.p[i] - b->pressure_at(P.x[i]));
    P.written(P.p);
  }

  // The buffers' drift from t to t + dt: inlet particles at the prescribed velocity of the step's middle
  // (exact for a uniform inflow), outlet particles at their own; then the inlets' velocity at t + dt.
  void drift(Particles<D>& P, double t, double dt) const {
    if (b_.empty()) return;
    for (std::size_t i = 0; i < P.n_owned; ++i) {
      if (P.kind[i] == kOutlet) P.x[i] += dt * P.v[i];
      if (P.kind[i] != kInlet) continue;
      if (const OpenBoundary<D>* b = boundary_of(P, i)) P.x[i] += dt * b->velocity_at(P.x[i], t + 0.5 * dt);
    }
    prescribe(P, t + dt);
  }

  // After a step: inlet particles inside the box become fluid and a new inlet particle takes each one's
  // place a buffer depth behind; fluid beyond an outlet's plane becomes outlet (its pressure the
  // outlet's, its density density_of(pressure)), outlet particles back inside become fluid, and those
  // beyond the buffer leave. Returns whether any particle changed (the caller rebuilds the lists: the
  // ghosts' kinds and the count changed). Collective.
  template <class DensityOf> bool exchange(Particles<D>& P, double t, DensityOf&& density_of) {
    if (b_.empty()) return false;
    std::vector<std::size_t> entered;
    std::vector<char> gone(P.n_owned, 0);
    int changed = 0;
    double out[2] = {0.0, 0.0};  // net particles and mass out through the outlets' planes
    for (std::size_t i = 0; i < P.n_owned; ++i) {
      if (P.kind[i] == kInlet) {
        const OpenBoundary<D>* b = boundary_of(P, i);
        if (b && b->beyond(P.x[i]) < 0.0) entered.push_back(i);
      } else if (P.kind[i] == kOutlet) {
        const OpenBoundary<D>* b = boundary_of(P, i);
        if (!b) continue;
        if (b->beyond(P.x[i]) > b->depth) gone[i] = 1, changed = 1;
        else if (b->beyond(P.x[i]) < 0.0) P.kind[i] = kFluid, changed = 1, out[0] -= 1.0, out[1] -= P.m[i];
      } else if (P.kind[i] == kFluid) {
        for (const OpenBoundary<D>& b : b_)
          if (b.type == OpenBoundary<D>::Type::Outlet && b.beyond(P.x[i]) >= 0.0) {
            P.kind[i] = kOutlet, changed = 1;
            if (outlet_pressure_ == OutletPressure::Fixed)
              P.p[i] = b.pressure_at(P.x[i]), P.rho[i] = density_of(P.p[i]);
            else P.fields[entered_][i] = 1.0;
            out[0] += 1.0, out[1] += P.m[i];
            break;
          }
      }
    }
    const std::size_t old_n = P.n_owned;
    const long long created = static_cast<long long>(entered.size());
    if (!entered.empty()) changed = 1;
    MPI_Allreduce(MPI_IN_PLACE, &changed, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
    if (!changed) return false;
    if (outlet_pressure_ == OutletPressure::Transmissive) P.written(P.fields[entered_]);
    // New inlet particles, one buffer depth behind those that entered, with ids from next_id (the
    // ranks in order).
    long long first = 0;
    MPI_Exscan(&created, &first, 1, MPI_LONG_LONG, MPI_SUM, PETSC_COMM_WORLD);
    PetscMPIInt rank;
    MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
    if (rank == 0) first = 0;
    long long total_created = 0;
    MPI_Allreduce(&created, &total_created, 1, MPI_LONG_LONG, MPI_SUM, PETSC_COMM_WORLD);
    P.set_ghost_count(0);
    double in[2] = {0.0, 0.0};
    for (std::size_t k = 0; k < entered.size(); ++k) {
      const std::size_t i = entered[k];
      const OpenBoundary<D>* b = boundary_of(P, i);
      const Vector<D> x = P.x[i] - b->depth * b->inward();
      P.add(x, b->velocity_at(x, t), P.m[i], P.rho[i], P.p[i], kInlet);
      P.fields.copy_row(P.n_owned - 1, i);
      P.id.back() = next_id_ + first + static_cast<long long>(k);
      P.kind[i] = kFluid;
      in[0] += 1.0, in[1] += P.m[i];
    }
    next_id_ += total_created;
    // Removed in place (the others keep their order), then renumbered.
    remove_particles_if(P, [&](std::size_t i) { return i < old_n && gone[i]; });
    double sums[4] = {in[0], in[1], out[0], out[1]};
    MPI_Allreduce(MPI_IN_PLACE, sums, 4, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
    flux_.in_count += static_cast<long long>(sums[0]), flux_.in_mass += sums[1];
    flux_.out_count += static_cast<long long>(sums[2]), flux_.out_mass += sums[3];
    return true;
  }

  const OpenBoundaryFlux& flux() const { return flux_; }

  // The ids new particles take start at the largest id so far + 1 (collective).
  void start_ids(const Particles<D>& P) {
    GlobalIndex largest = -1;
    for (std::size_t i = 0; i < P.n_owned; ++i) largest = std::max(largest, P.id[i]);
    MPI_Allreduce(MPI_IN_PLACE, &largest, 1, MPIU_INT, MPI_MAX, PETSC_COMM_WORLD);
    next_id_ = static_cast<long long>(largest) + 1;
  }
  long long next_id() const { return next_id_; }

  // The state a restart needs: the next id, the fluxes so far and the outlets' last mean velocity.
  nlohmann::json state() const {
    return {{"next_id", next_id_},
            {"inflow", {{"particles", flux_.in_count}, {"mass", flux_.in_mass}}},
            {"outflow", {{"particles", flux_.out_count}, {"mass", flux_.out_mass}}},
            {"outlet_mean_outward_velocity", last_outward_}};
  }
  void restore(const nlohmann::json& s) {
    if (!s.is_object()) return;
    next_id_ = s.value("next_id", next_id_);
    last_outward_ = s.value("outlet_mean_outward_velocity", std::vector<double>());
    flux_.in_count = s["inflow"].value("particles", 0LL), flux_.in_mass = s["inflow"].value("mass", 0.0);
    flux_.out_count = s["outflow"].value("particles", 0LL), flux_.out_mass = s["outflow"].value("mass", 0.0);
  }

 private:
  std::vector<OpenBoundary<D>> b_;
  long long next_id_ = 0;
  OpenBoundaryFlux flux_;
  // Per boundary, the mean outward velocity across its section, over the fluid and its own buffer's
  // particles within `slab` of its plane, each weighted by (1 - distance / slab)^2 so that a particle's
  // weight falls to zero where it joins or leaves the slab (zero for inlets). Collective.
  std::vector<double> mean_outward_velocities(const Particles<D>& P, double slab) const {
    std::vector<double> sums(2 * b_.size(), 0.0);
    for (std::size_t i = 0; i < P.n_owned; ++i) {
      if (P.kind[i] != kFluid && P.kind[i] != kOutlet) continue;
      for (std::size_t k = 0; k < b_.size(); ++k) {
        const OpenBoundary<D>& b = b_[k];
        const double d = std::abs(b.beyond(P.x[i]));
        if (b.type != OpenBoundary<D>::Type::Outlet || d >= slab || !b.in_section(P.x[i])) continue;
        if (P.kind[i] == kOutlet && boundary_of(P, i) != &b) continue;
        const double w = (1.0 - d / slab) * (1.0 - d / slab);
        sums[2 * k] -= w * P.v[i].dot(b.inward()), sums[2 * k + 1] += w;
      }
    }
    MPI_Allreduce(MPI_IN_PLACE, sums.data(), static_cast<int>(sums.size()), MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
    std::vector<double> mean(b_.size(), 0.0);
    for (std::size_t k = 0; k < b_.size(); ++k)
      if (sums[2 * k + 1] > 0.0) mean[k] = sums[2 * k] / sums[2 * k + 1];
    return mean;
  }

  // Per boundary, the fluid's wetted section beside its plane: the volume of the fluid within `slab`
  // inside it, each particle weighted by (1 - distance / slab)^2, over the weight's integral slab / 3
  // (2D: the depth; 3D: the area). Zero where the boundary keeps no level. Collective.
  std::vector<double> wetted_sections(const Particles<D>& P, double slab) const {
    std::vector<double> volume(b_.size(), 0.0);
    for (std::size_t i = 0; i < P.n_owned; ++i) {
      if (P.kind[i] != kFluid) continue;
      for (std::size_t k = 0; k < b_.size(); ++k) {
        const OpenBoundary<D>& b = b_[k];
        const double d = -b.beyond(P.x[i]);
        if (!b.keeps_level || d < 0.0 || d >= slab || !b.in_section(P.x[i])) continue;
        volume[k] += (1.0 - d / slab) * (1.0 - d / slab) * P.m[i] / P.rho[i];
      }
    }
    MPI_Allreduce(MPI_IN_PLACE, volume.data(), static_cast<int>(volume.size()), MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
    for (double& v : volume) v *= 3.0 / slab;
    return volume;
  }

  OutletPressure outlet_pressure_ = OutletPressure::Fixed;
  double impedance_ = 0.0;            // rho0 c0 (transmissive outlets)
  FieldId<double> entered_;           // 1: just left the fluid (transmissive outlets)
  std::vector<double> last_outward_;  // per boundary, at the last transmit_outlet_pressure (empty: none yet)
};

}  // namespace sph
