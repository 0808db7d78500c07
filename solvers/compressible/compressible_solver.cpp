#include "solvers/compressible/compressible_solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "src/core/log_events.hpp"
#include "src/core/options.hpp"
#include "src/sph/leapfrog.hpp"

namespace sph {

namespace {
// The neighbour search reaches kSearchHeadroom times the largest support: smoothing lengths drift by a
// fraction of a percent per step, so the search radius need not change every step. It shrinks again
// once the largest support falls below kSearchShrink of it (after an expansion, say).
constexpr double kSearchHeadroom = 1.1, kSearchShrink = 0.7;
// Density and smoothing length: Newton-Raphson, safeguarded by bisection from iteration
// kNewtonIterationsBeforeBisection on; a particle not converged after kMaxDensityIterations is an error.
constexpr int kNewtonIterationsBeforeBisection = 10, kMaxDensityIterations = 80;

// This scheme's phases in -log_view, beside the core's (src/core/log_events.hpp): density and smoothing
// length by Newton-Raphson (grad-h), and the pruned pair lists.
PetscLogEvent density_h_event() {
  static const PetscLogEvent e = register_log_event("SPHGasDensityH");
  return e;
}
PetscLogEvent pairs_event() {
  static const PetscLogEvent e = register_log_event("SPHGasPairs");
  return e;
}

double mpi_max(double x) {
  MPI_Allreduce(MPI_IN_PLACE, &x, 1, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
  return x;
}

}  // namespace

template <int D> void CompressibleSolver<D>::setup(Discretisation<D>& disc) {
  refuse_unmodelled_open_boundaries(disc, name(), false);
  disc_ = &disc;
  Particles<D>& P = disc.particles;
  const Physics<D>& phys = disc.physics;
  if (!phys.is_gas())
    throw Error(
        "the compressible solver needs a gas scene (the case declares no adiabatic index gamma); "
        "use e.g. -case sod or -case toy_star, or another -solver");
  require(phys.gamma > 1.0, "gamma (declared by the case)", "greater than 1", phys.gamma);
  if (phys.viscous())
    throw Error("the compressible solver has no physical (Navier-Stokes) viscosity; the case asks for nu > 0");
  gamma_ = phys.gamma;
  entropy_ = phys.isentropic;
  const KernelType type = disc.kernel.type();
  kappa_ = Kernel<D>::support_factor(type);
  if (eta_ == 0.0) eta_ = Kernel<D>::default_eta(type);

  declare_fields(P);
  const Fields f = fields();
  const std::size_t n = P.n_owned;
  f.h.assign(n, 0.0), f.thermal.assign(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    if (P.kind[i] != kFluid)
      throw Error("the compressible solver has no wall boundary treatment; use a periodic or free case");
    if (!(P.rho[i] > 0.0 && P.p[i] >= 0.0))
      throw Error("the compressible solver needs positive initial densities and non-negative pressures");
    f.h[i] = eta_ * std::pow(P.m[i] / P.rho[i], 1.0 / D);
  }
  // The case's pressure and density set the entropy function A = P / rho^gamma (isentropic scenes).
  if (entropy_)
    for (std::size_t i = 0; i < n; ++i) f.thermal[i] = P.p[i] / std::pow(P.rho[i], gamma_);
  std::vector<double> p_case(P.p.begin(), P.p.begin() + n);
  const double alpha0 =
      switch_ == ViscositySwitch::MorrisMonaghan ? std::clamp<double>(av_.alpha, alpha_min_, alpha_max_) : av_.alpha;
  f.alpha.assign(n, alpha0);
  f.dalpha.assign(n, 0.0);

  double h_max = 0.0;
  for (std::size_t i = 0; i < n; ++i) h_max = std::max(h_max, f.h[i]);
  disc.neighbourhood.set_support_radius(kSearchHeadroom * kappa_ * mpi_max(h_max));
  disc.neighbourhood.update(P, true);
  prune_pairs();
  solve_density();
  // With the energy equation, u = P / ((gamma - 1) rho) from the summation density keeps the case's
  // pressure exactly (at a discontinuity the summation density is smoothed over h; a thermal energy from
  // the case's density would give a pressure blip there that runs off as a spurious wave).
  if (!entropy_)
    for (std::size_t i = 0; i < n; ++i) f.thermal[i] = p_case[i] / ((gamma_ - 1.0) * P.rho[i]);
  update_thermodynamics();
  compute_forces();
  energy0_ = total_energy();
  momentum0_ = total_momentum();
  double scale = 0.0;
  for (std::size_t i = 0; i < n; ++i) scale += P.m[i] * P.v[i].norm();
  MPI_Allreduce(MPI_IN_PLACE, &scale, 1, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  momentum_scale0_ = scale;
}

// What a restart needs to continue exactly moves with the particles: the leapfrog's rates, the thermal
// state and the viscosity switch, h (the Newton start) and the signal speeds (the step size).
template <int D> void CompressibleSolver<D>::declare_fields(Particles<D>& P) {
  FieldRegistry<D>& r = P.fields;
  const std::size_t rows = P.size();
  ids_.h = r.declare_scalar("smoothing_length", kCarried | kWritten, rows);
  ids_.u = r.declare_scalar("internal_energy", kCarried | kWritten, rows);
  ids_.thermal = r.declare_scalar("thermal_variable", kCarried, rows);
  ids_.alpha = r.declare_scalar("alpha", kCarried, rows);
  ids_.acc = r.declare_vector("acceleration", kCarried, rows);
  ids_.dthermal = r.declare_scalar("thermal_rate", kCarried, rows);
  ids_.dalpha = r.declare_scalar("alpha_rate", kCarried, rows);
  ids_.vsig = r.declare_scalar("signal_velocity", kCarried, rows);
}

template <int D> typename CompressibleSolver<D>::Fields CompressibleSolver<D>::fields() const {
  FieldRegistry<D>& r = disc_->particles.fields;
  return {r[ids_.h],   r[ids_.u],        r[ids_.thermal], r[ids_.alpha],
          r[ids_.acc], r[ids_.dthermal], r[ids_.dalpha],  r[ids_.vsig]};
}

template <int D> void CompressibleSolver<D>::ensure_search_radius(double h_max, bool allow_shrink) {
  Neighbourhood<D>& nh = disc_->neighbourhood;
  const double need = kappa_ * h_max;
  if (need > nh.support_radius() || (allow_shrink && need < kSearchShrink * nh.support_radius())) {
    nh.set_support_radius(kSearchHeadroom * need);
    nh.update(disc_->particles, true);
    ++radius_changes_;
  }
}

// Margin of the pruned lists over kappa h: smoothing lengths change by well under 1% per step.
constexpr double prune_margin = 1.2;

template <int D> void CompressibleSolver<D>::prune_pairs() {
  const Fields f = fields();
  const LogEventScope log_pairs(pairs_event());
  Particles<D>& P = disc_->particles;
  const Neighbourhood<D>& nh = disc_->neighbourhood;
  // The pruning reads the neighbours' h, which the density iteration has just changed on the owned
  // particles: no pair loop has refreshed their ghosts yet, so they are refreshed here, by hand.
  f.h.resize(P.n_owned);
  nh.halo().update(f.h);
  pairs_.build(P, nh.list(), f.h, kappa_, prune_margin);
  pairs_built_at_rebuild_ = nh.rebuilds();
}

template <int D> bool CompressibleSolver<D>::pairs_valid() const {
  const Fields f = fields();
  if (pairs_built_at_rebuild_ != disc_->neighbourhood.rebuilds() || pairs_.size() != disc_->particles.n_owned)
    return false;
  int ok = 1;
  for (std::size_t i = 0; i < pairs_.size() && ok; ++i) ok = kappa_ * f.h[i] <= pairs_.reach(i);
  MPI_Allreduce(MPI_IN_PLACE, &ok, 1, MPI_INT, MPI_MIN, PETSC_COMM_WORLD);
  return ok;
}

// One Newton step of particle i's smoothing length: the density and its h-derivative summed at the
// current h (with div v and |curl v| where the switches need them); true, with rho, omega and the
// velocity's derivatives stored, when h has converged, else h moved to its update.
template <int D> bool CompressibleSolver<D>::newton_h_step(const Fields& f, const NeighbourList<D>& nl, std::size_t i,
                                                           int iteration, compressible::HBracket& bracket,
                                                           bool need_div) {
  using namespace compressible;
  Particles<D>& P = disc_->particles;
  const KernelType type = disc_->kernel.type();
  const double h = f.h[i];
  const Kernel<D> K(type, h);
  DensitySums s;
  const double W0 = K.W(0.0);
  s.rho = P.m[i] * W0;
  s.drho_dh = P.m[i] * dW_dh(D, W0, 0.0, 0.0, h);
  double div = 0.0;
  Eigen::Vector3d curl = Eigen::Vector3d::Zero();
  auto gather = [&](int j, const Vector<D>& rij, double r) {
    const double W = K.W(r), dW = K.dWdr(r);
    s.rho += P.m[j] * W;
    s.drho_dh += P.m[j] * dW_dh(D, W, r, dW, h);
    if (need_div) {
      const Vector<D> vij = P.v[i] - P.v[j], gradW = (dW / r) * rij;
      div += divergence_term(P.m[j], vij, gradW);
      curl += curl_term(P.m[j], vij, gradW);
    }
  };
  // The pruned list while it covers this h, the full list when the iteration has gone beyond it.
  if (K.support_radius() <= pairs_.reach(i)) for_each_gather_neighbour(P, pairs_, i, K, gather);
  else for_each_gather_neighbour(P, nl, i, K, gather);
  const double h_new = newton_h_update(D, P.m[i], eta_, h, s, bracket, iteration > kNewtonIterationsBeforeBisection);
  const bool closed = bracket.hi > 0.0 && bracket.hi - bracket.lo <= h_tolerance_ * h;
  if (std::abs(h_new - h) <= h_tolerance_ * h || closed) {
    // Converged: the sums were taken at this h.
    P.rho[i] = s.rho;
    omega_[i] = grad_h_factor(D, h, s);
    if (need_div) divv_[i] = div / (omega_[i] * s.rho), curlv_[i] = curl.norm() / (omega_[i] * s.rho);
    return true;
  }
  f.h[i] = h_new;
  return false;
}

template <int D> void CompressibleSolver<D>::solve_density() {
  const Fields f = fields();
  using namespace compressible;
  const LogEventScope log_density_h(density_h_event());
  Particles<D>& P = disc_->particles;
  const std::size_t n = P.n_owned;
  const bool need_div = switch_ == ViscositySwitch::MorrisMonaghan || balsara_;
  omega_.resize(std::max(omega_.size(), n));
  divv_.assign(n, 0.0), curlv_.assign(n, 0.0);

  std::vector<std::size_t> active(n);
  for (std::size_t i = 0; i < n; ++i) active[i] = i;
  std::vector<HBracket> bracket(n);
  const int max_iterations = kMaxDensityIterations;
  for (int iteration = 1;; ++iteration) {
    double h_max = 0.0;
    for (std::size_t k : active) h_max = std::max(h_max, f.h[k]);
    ensure_search_radius(mpi_max(h_max), false);
    if (pairs_built_at_rebuild_ != disc_->neighbourhood.rebuilds()) prune_pairs();
    const NeighbourList<D>& nl = disc_->neighbourhood.list();
    check_position_ghosts(P, nl);
    check_ghosts(nl, P.m, "m");
    if (need_div) check_ghosts(nl, P.v, "v");

    // Threads share the active particles; each writes only its own entries. Which ones stay active
    // is collected afterwards, in order.
    std::vector<char> converged(active.size(), 0);
    const std::ptrdiff_t n_active = static_cast<std::ptrdiff_t>(active.size());
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t k = 0; k < n_active; ++k)
      converged[k] = newton_h_step(f, nl, active[k], iteration, bracket[active[k]], need_div);
    std::vector<std::size_t> still;
    for (std::size_t k = 0; k < active.size(); ++k)
      if (!converged[k]) still.push_back(active[k]);
    active.swap(still);
    density_iterations_max_ = std::max<long>(density_iterations_max_, iteration);
    double left = static_cast<double>(active.size());
    MPI_Allreduce(MPI_IN_PLACE, &left, 1, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
    if (left == 0.0) break;
    if (iteration == max_iterations) {
      std::ostringstream msg;
      msg << "the smoothing-length iteration did not converge in " << max_iterations << " Newton steps ("
          << static_cast<long>(left) << " particles left, e.g. at x = " << P.x[active.front()].transpose()
          << "); reduce -acoustic_cfl or raise -h_tolerance";
      throw Error(msg.str());
    }
  }
  double h_max = 0.0, h_min = std::numeric_limits<double>::max();
  for (std::size_t i = 0; i < n; ++i) h_max = std::max(h_max, f.h[i]), h_min = std::min(h_min, f.h[i]);
  h_max_seen_ = mpi_max(h_max);
  h_min_seen_ = -mpi_max(-h_min);
  ensure_search_radius(h_max_seen_, true);  // narrow the search again where the gas was compressed
}

template <int D> void CompressibleSolver<D>::update_thermodynamics() {
  const Fields f = fields();
  const LogEventScope log_density(LogEvent::Density);
  Particles<D>& P = disc_->particles;
  const std::size_t n = P.n_owned;
  f.u.resize(n), cs_.resize(n), balsara_factor_.resize(n), q_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double rho = P.rho[i];
    if (entropy_) {
      P.p[i] = f.thermal[i] * std::pow(rho, gamma_);
      f.u[i] = P.p[i] / ((gamma_ - 1.0) * rho);
    } else {
      f.u[i] = f.thermal[i];
      P.p[i] = (gamma_ - 1.0) * rho * f.u[i];
    }
    cs_[i] = std::sqrt(gamma_ * P.p[i] / rho);
    balsara_factor_[i] = balsara_ ? compressible::balsara_factor(divv_[i], curlv_[i], cs_[i], f.h[i]) : 1.0;
    q_[i] = P.p[i] / (omega_[i] * rho * rho);
  }
  const Halo<D>& halo = disc_->neighbourhood.halo();
  halo.update(P.rho), halo.update(P.p), halo.update(f.h), halo.update(f.u), halo.update(cs_), halo.update(q_);
  if (av_.active()) halo.update(f.alpha), halo.update(balsara_factor_);
  omega_.resize(n), halo.update(omega_);
  const KernelType type = disc_->kernel.type();
  kernels_.clear();
  kernels_.reserve(P.size());
  for (std::size_t k = 0; k < P.size(); ++k) kernels_.emplace_back(type, f.h[k]);
}

template <int D> void CompressibleSolver<D>::compute_forces() {
  const Fields f = fields();
  using namespace compressible;
  const LogEventScope log_forces(LogEvent::Forces);
  Particles<D>& P = disc_->particles;
  const Physics<D>& phys = disc_->physics;
  const std::size_t n = P.n_owned;
  f.acc.assign(n, phys.gravity);
  if (phys.has_external_force())
    for (std::size_t i = 0; i < n; ++i) f.acc[i] += phys.external_acceleration(P.x[i]);
  std::vector<double> pdv(n, 0.0), heat(n, 0.0);
  f.vsig.assign(n, 0.0);

  if (!pairs_valid()) prune_pairs();
  check_ghosts(pairs_, f.h, "h"), check_ghosts(pairs_, q_, "q"), check_ghosts(pairs_, cs_, "cs");
  if (av_.active()) check_ghosts(pairs_, f.alpha, "alpha"), check_ghosts(pairs_, balsara_factor_, "balsara_factor");
  if (conductivity_) check_ghosts(pairs_, f.u, "u");
  for_each_variable_h_pair(P, pairs_, kernels_, [&](int i, int j, const VariableHPair<D>& g) {
    const Vector<D> vij = P.v[i] - P.v[j];
    f.acc[i] += pressure_acceleration(P.m[j], q_[i], q_[j], g);
    pdv[i] += pdv_heating(P.m[j], q_[i], vij, g);
    f.vsig[i] = std::max(f.vsig[i], signal_velocity(cs_[i], cs_[j], vij.dot(g.rij) / g.r));
    if (av_.active()) {
      const double alpha_ij = 0.25 * (f.alpha[i] + f.alpha[j]) * (balsara_factor_[i] + balsara_factor_[j]);
      const double Pi = av_.Pi(alpha_ij, cs_[i], cs_[j], P.rho[i], P.rho[j], f.h[i], f.h[j], vij, g);
      if (Pi > 0.0) {
        f.acc[i] += viscous_acceleration(P.m[j], Pi, g);
        heat[i] += viscous_heating(P.m[j], Pi, vij, g);
      }
    }
    if (conductivity_)
      heat[i] +=
          conductivity_heating(P.m[j], alpha_u_, P.p[i], P.p[j], P.rho[i], P.rho[j], f.u[i], f.u[j], g.dW_mean());
  });

  f.dthermal.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    // In entropy mode only dissipation changes A: dA/dt = (gamma - 1) rho^(1 - gamma) du/dt|_diss.
    f.dthermal[i] = entropy_ ? (gamma_ - 1.0) * std::pow(P.rho[i], 1.0 - gamma_) * heat[i] : pdv[i] + heat[i];
  f.dalpha.assign(n, 0.0);
  if (switch_ == ViscositySwitch::MorrisMonaghan)
    for (std::size_t i = 0; i < n; ++i)
      f.dalpha[i] = morris_monaghan_rate(f.alpha[i], alpha_min_, alpha_max_, mm_sigma_, divv_[i], cs_[i], f.h[i]);
}

template <int D> double CompressibleSolver<D>::stable_dt() const {
  const Fields f = fields();
  const Particles<D>& P = disc_->particles;
  double dt = std::numeric_limits<double>::max();
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    if (f.vsig[i] > 0.0) dt = std::min(dt, cfl_ * f.h[i] / f.vsig[i]);
    const double a = f.acc[i].norm();
    if (a > 0.0) dt = std::min(dt, cfl_force_ * std::sqrt(f.h[i] / a));
  }
  dt = -mpi_max(-dt);
  // A gas without pressure or neighbours: the reference speed bounds the step.
  if (dt == std::numeric_limits<double>::max()) dt = cfl_ * h_min_seen_ / std::max(disc_->physics.U, 1e-300);
  return dt;
}

template <int D> void CompressibleSolver<D>::check_thermal_state() const {
  const Fields f = fields();
  const Particles<D>& P = disc_->particles;
  int bad = -1;
  for (std::size_t i = 0; i < P.n_owned && bad < 0; ++i)
    if (!(f.thermal[i] >= 0.0) || !std::isfinite(f.thermal[i])) bad = static_cast<int>(i);
  int any = bad >= 0;
  MPI_Allreduce(MPI_IN_PLACE, &any, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
  if (!any) return;
  std::ostringstream msg;
  msg << (entropy_ ? "entropy function" : "thermal energy") << " became negative or NaN";
  if (bad >= 0) msg << " (particle at x = " << P.x[bad].transpose() << ")";
  msg << "; reduce -acoustic_cfl or raise -av_alpha";
  throw Error(msg.str());
}

template <int D> StepReport CompressibleSolver<D>::step(double dt) {
  const Fields f = fields();
  Particles<D>& P = disc_->particles;
  const std::size_t n = P.n_owned;
  const bool mm = switch_ == ViscositySwitch::MorrisMonaghan;
  // Kick-drift-kick; velocity, thermal variable and viscosity switch are predicted to t^{n+1} for the
  // velocity- and energy-dependent terms of the force evaluation.
  std::vector<LeapfrogScalar> scalars = {{&f.thermal, &f.dthermal}};
  if (mm) scalars.push_back({&f.alpha, &f.dalpha, alpha_min_, alpha_max_});
  leapfrog_step<D>(
      dt, n, P.x, P.v, f.acc, scalars, [](std::size_t) { return true; },
      [&] {
        check_thermal_state();
        disc_->neighbourhood.update(P);
        prune_pairs();  // particles moved: distances changed
        solve_density();
        update_thermodynamics();
        compute_forces();
      });
  check_thermal_state();
  // Pressure and thermal energy of the final state (what the outputs and the errors see).
  for (std::size_t i = 0; i < n; ++i) {
    if (entropy_) {
      P.p[i] = f.thermal[i] * std::pow(P.rho[i], gamma_);
      f.u[i] = P.p[i] / ((gamma_ - 1.0) * P.rho[i]);
    } else {
      f.u[i] = f.thermal[i];
      P.p[i] = (gamma_ - 1.0) * P.rho[i] * f.u[i];
    }
  }
  return {};
}

template <int D> double CompressibleSolver<D>::total_energy() const {
  const Fields f = fields();
  const Particles<D>& P = disc_->particles;
  const Physics<D>& phys = disc_->physics;
  double E = 0.0;
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    double e = 0.5 * P.v[i].squaredNorm() + f.u[i] - phys.gravity.dot(P.x[i]);
    if (phys.external_potential) e += phys.external_potential(P.x[i]);
    E += P.m[i] * e;
  }
  MPI_Allreduce(MPI_IN_PLACE, &E, 1, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  return E;
}

template <int D> Vector<D> CompressibleSolver<D>::total_momentum() const {
  const Particles<D>& P = disc_->particles;
  Vector<D> M = Vector<D>::Zero();
  for (std::size_t i = 0; i < P.n_owned; ++i) M += P.m[i] * P.v[i];
  MPI_Allreduce(MPI_IN_PLACE, M.data(), D, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  return M;
}

template <int D> nlohmann::json CompressibleSolver<D>::checkpoint_scalars() const {
  return {{"energy_initial", energy0_},
          {"momentum_initial", std::vector<double>(momentum0_.data(), momentum0_.data() + D)},
          {"momentum_scale_initial", momentum_scale0_},
          {"search_radius", disc_->neighbourhood.support_radius()},
          {"density_iterations_max", density_iterations_max_},
          {"search_radius_changes", radius_changes_},
          {"h_range", {h_min_seen_, h_max_seen_}}};
}

template <int D> void CompressibleSolver<D>::restore_scalars(const nlohmann::json& j) {
  energy0_ = j.at("energy_initial").get<double>();
  const auto m = j.at("momentum_initial").get<std::vector<double>>();
  for (int a = 0; a < D; ++a) momentum0_[a] = m.at(a);
  momentum_scale0_ = j.at("momentum_scale_initial").get<double>();
  density_iterations_max_ = j.at("density_iterations_max").get<long>();
  radius_changes_ = j.at("search_radius_changes").get<long>();
  h_min_seen_ = j.at("h_range")[0].get<double>(), h_max_seen_ = j.at("h_range")[1].get<double>();
  disc_->neighbourhood.set_support_radius(j.at("search_radius").get<double>());  // the driver rebuilds next
}

template class CompressibleSolver<1>;
template class CompressibleSolver<2>;
template class CompressibleSolver<3>;

}  // namespace sph
