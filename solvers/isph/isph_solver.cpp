#include "solvers/isph/isph_solver.hpp"

#include <cmath>
#include <utility>

#include "src/boundary/adami_wall_model.hpp"
#include "src/core/log_events.hpp"
#include "src/core/options.hpp"
#include "src/sph/free_surface.hpp"
#include "src/sph/operators.hpp"
#include "src/sph/step_limits.hpp"

namespace sph {

namespace {
// This scheme's phases in -log_view, beside the core's (src/core/log_events.hpp): the PPE's source,
// free-surface flags and matrix; the pressure solve (KSPSolve, whose PCSetUp PETSc logs itself).
PetscLogEvent ppe_assembly_event() {
  static const PetscLogEvent e = register_log_event("SPHPPEAssembly");
  return e;
}
PetscLogEvent ppe_solve_event() {
  static const PetscLogEvent e = register_log_event("SPHPPESolve");
  return e;
}

}  // namespace

template <int D> void IsphSolver<D>::setup(Discretisation<D>& disc) {
  refuse_unmodelled(disc.physics, name(), false, false);
  refuse_unmodelled_open_boundaries(disc, name(), true);
  disc_ = &disc;
  Particles<D>& P = disc.particles;
  // Divergence-free ISPH: density stays at its reference value (walls included).
  for (std::size_t i = 0; i < P.n_owned; ++i) P.rho[i] = disc.physics.rho0;
  walls_ = has_walls(P);
  disc.walls = make_wall_model<D>(wall_pressure_, disc.bodies);
  ppe_.walls = disc.walls.get();
  energy_ = EnergyBudget(disc.physics.gravity, disc.neighbourhood.domain().periodic);
  // Inlet rows extrapolate as wall rows do; outlet rows hold their pressure.
  ppe_.use_nonsymmetric(walls_ || disc.physics.free_surface || operators_ == OperatorSet::Consistent ||
                        disc.open.any());
  // The last step's mean pressure pm moves with its particle (migration, checkpoints).
  mean_pressure_ = P.fields.declare_scalar("mean_step_pressure", kCarried, P.size());
  free_surface_model_.setup(P, disc.physics.free_surface,
                            BandScan::All);  // its surface rows need every surface particle
  // The impact term only if asked for: in a closed domain it adds the noise of the walls' normals at
  // corners ("Design measurements"), and with a free surface, a pressure applied once per step, it fed
  // the flow energy as the step fell. There the bounding, which only takes energy away, stops the fluid
  // that comes at a wall (docs/verification/free_surface.md, "The time step moves ISPH's answer").
  wall_impact_ = walls_ && wall_impact_option_ > 0;
  bound_to_walls_ = walls_ && (wall_bounding_option_ < 0 ? disc.physics.free_surface : wall_bounding_option_ > 0);
  // Along a through-flow the particles' volume error grows with their path; in a closed box it cannot.
  density_relaxation_ = density_relaxation_option_ < 0 ? (disc.open.any() ? 1.0 : 0.0) : density_relaxation_option_;
  disc.neighbourhood.update(P, true);
}

template <int D> double IsphSolver<D>::max_speed() const {
  const Particles<D>& P = disc_->particles;
  double u2 = 0.0;
  for (std::size_t i = 0; i < P.n_owned; ++i) u2 = std::max(u2, P.v[i].squaredNorm());
  MPI_Allreduce(MPI_IN_PLACE, &u2, 1, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
  return std::sqrt(u2);
}

template <int D> double IsphSolver<D>::stable_dt() const {
  const double h = disc_->kernel.h();
  const Physics<D>& phys = disc_->physics;
  // The reference speed bounds the step too, so a fluid at rest does not take an unbounded step.
  double dt = cfl_ * h / std::max(max_speed(), phys.U);
  if (phys.viscous()) dt = std::min(dt, kViscousStepFactor * h * h / phys.nu);  // Morris et al. (1997)
  return dt;
}

// The corrected and consistent operators are evaluated at fluid particles only (Rows::Fluid): walls
// keep their prescribed velocity, their PPE rows extrapolate the fluid pressure, and nothing reads an
// operator's value at a wall.
template <int D> std::vector<Vector<D>> IsphSolver<D>::pressure_gradient(const std::vector<double>& p) const {
  const Particles<D>& P = disc_->particles;
  const NeighbourList<D>& nl = disc_->neighbourhood.list();
  const Kernel<D>& K = disc_->kernel;
  switch (gradient_) {
    case PressureGradient::Corrected:
      return nodes_.empty() ? gradient_corrected(P, nl, K, p, Rows::Fluid)
                            : gradient_corrected(P, nl, K, p, Rows::Fluid, nodes_);
    case PressureGradient::Difference: return gradient_difference(P, nl, K, p);
    case PressureGradient::Symmetric: return gradient_symmetric(P, nl, K, p);
  }
  return {};
}

template <int D> std::vector<LaplacianCorrection<D>> IsphSolver<D>::laplacian_corrections_if_used() const {
  if (operators_ != OperatorSet::Consistent) return {};
  const Neighbourhood<D>& nh = disc_->neighbourhood;
  return laplacian_corrections(disc_->particles, nh.list(), disc_->kernel, Rows::Fluid);
}

template <int D>
std::vector<Vector<D>> IsphSolver<D>::viscous_acceleration(const std::vector<Vector<D>>& u,
                                                           std::vector<LaplacianCorrection<D>>* factors) const {
  const Particles<D>& P = disc_->particles;
  const Neighbourhood<D>& nh = disc_->neighbourhood;
  const Kernel<D>& K = disc_->kernel;
  // No-slip walls: the viscous term sees the mirrored wall velocity (Adami et al. 2012).
  std::vector<Vector<D>> u_wall;
  if (walls_) u_wall = disc_->walls->viscous_velocity(P, nh, K, u);
  const std::vector<Vector<D>>& uv = walls_ ? u_wall : u;
  if (operators_ != OperatorSet::Consistent) {
    std::vector<Vector<D>> lap = laplacian_morris(P, nh.list(), K, uv);
    for (auto& a : lap) a *= disc_->physics.nu;
    return lap;
  }
  std::vector<LaplacianCorrection<D>> own_factors;
  std::vector<LaplacianCorrection<D>>& F = factors ? *factors : own_factors;
  std::vector<Vector<D>> lap = laplacian_consistent_one_pass(P, nh.list(), K, uv, Rows::Fluid, &F);
  // The surface cuts the supports there, where the fourth moments are one-sided, not isotropic.
  if (viscous_laplacian_ == ViscousLaplacian::Fourth && !disc_->physics.free_surface)
    remove_laplacian_smoothing_error(P, nh, K, F, lap);
  for (auto& a : lap) a *= disc_->physics.nu;
  return lap;
}

template <int D> std::vector<std::vector<double>> IsphSolver<D>::ppe_divergences(
    const std::vector<const std::vector<Vector<D>>*>& fields, const std::vector<char>& near_surface, double tau) const {
  const Particles<D>& P = disc_->particles;
  const NeighbourList<D>& nl = disc_->neighbourhood.list();
  const Kernel<D>& K = disc_->kernel;
  // The walls count as at rest (-ppe_wall_velocity zero, the default), as in WCSPH's continuity
  // equation: wall particles keep their place, so a wall's velocity is tangential and its normal
  // component, the only part the constraint needs, is zero. With the prescribed velocities the cavity's
  // lid beside the fixed downstream corner block is a jump U -> 0 that the divergence reads as a
  // compression of order U/dx there: it raises that corner's stagnation pressure and drives the vortex
  // harder, a first-order error that on coarse grids at Re 1000 happens to offset the under-resolved
  // vortex's weakness (docs/verification/lid_driven_cavity.md, "Why the best corner depends on Re").
  // A moving body's normal velocity is what the constraint is about: it keeps it.
  const Vector<D> g = disc_->physics.gravity;
  // The walls' entries below are written over the fields' ghost slots too, from P.v's: both fresh first.
  check_ghosts(nl, P.v, "the particles' velocity");
  for (const auto* u : fields) check_ghosts(nl, *u, "the divergence's field");
  std::vector<std::vector<Vector<D>>> at_rest;
  std::vector<const std::vector<Vector<D>>*> us = fields;
  const WallModel<D>& walls = *disc_->walls;
  if (source_walls_at_rest_ && walls_) {
    at_rest.reserve(fields.size());
    for (std::size_t f = 0; f < fields.size(); ++f) {
      at_rest.push_back(*fields[f]);
      for (std::size_t i = 0; i < at_rest[f].size(); ++i) {
        if (P.kind[i] != kWall) continue;
        const Vector<D> head = f == 0 ? Vector<D>(tau * (g - walls.acceleration(P, i))) : Vector<D>::Zero();
        at_rest[f][i] = walls.continuity_velocity(P, i) + head;
      }
      us[f] = &at_rest[f];
    }
  }
  std::vector<std::vector<double>> div;
  if (operators_ != OperatorSet::Consistent) {
    for (const auto* u : us) div.push_back(divergence(P, nl, K, *u));
    return div;
  }
  div = divergences_corrected(P, nl, K, us, Rows::Fluid, nodes_.empty() ? nullptr : &nodes_);
  // With p = 0 on the surface particles (-free_surface_condition particle) the corrected divergence
  // next to them extrapolates u into the empty half of the cut support and amplifies the noise of
  // those unconstrained particles, which blew up the dam break (docs/verification/dam_break.md, "ISPH at
  // nx 40, a blow-up found and fixed"): the plain one is used there.
  // Surface nodes complete the cut support instead, and divergences_corrected takes them in.
  if (!near_surface.empty())
    for (std::size_t f = 0; f < us.size(); ++f) {
      const std::vector<double> plain = divergence(P, nl, K, *us[f]);
      for (std::size_t i = 0; i < P.n_owned; ++i)
        if (near_surface[i]) div[f][i] = plain[i];
    }
  return div;
}

template <int D> StepReport IsphSolver<D>::project(const std::vector<Vector<D>>& u_star, double tau,
                                                   std::vector<LaplacianCorrection<D>> corrections) {
  Projection j;
  j.tau = tau;
  j.consistent = operators_ == OperatorSet::Consistent;
  j.nodes = disc_->physics.free_surface && surface_condition_ == SurfaceCondition::Node;
  j.corrections = std::move(corrections);

  // div(grad p / rho) = div(u*) / tau.
  LogEventScope log_assembly(ppe_assembly_event());
  detect_free_surface(j);
  const std::vector<double> source = ppe_source(u_star, j);
  if (wall_impact_) prepare_wall_impact(u_star, j);
  set_dirichlet_rows(j);
  // Moving bodies' rows extrapolate with g - a_w (Adami et al. 2012).
  j.wall_acceleration = disc_->walls->accelerations(disc_->particles);
  assemble(j);
  // Only a surface particle released below assembles again: otherwise the factors go before the
  // solve, where the step's memory peaks (docs/performance.md, "Memory per particle").
  if (!j.nodes) j.corrections = {};
  log_assembly.end();

  LogEventScope log_solve(ppe_solve_event());
  StepReport report = solve_releasing_tension(source, j);
  ++solves_;
  // After the step's last solve the system goes before the forces, which would otherwise add to the
  // step's memory peak (docs/performance.md, "Memory per particle").
  if (projection_corrections_ == 0) ppe_.release();
  log_solve.end();

  LogEventScope log_correction(LogEvent::Forces);
  Particles<D>& P = disc_->particles;
  const std::vector<Vector<D>> grad_p = pressure_gradient(P.p);
  for (std::size_t i = 0; i < P.n_owned; ++i)
    if (P.kind[i] == kFluid) P.v[i] = u_star[i] - (tau / P.rho[i]) * grad_p[i];
  P.written(P.v);
  log_correction.end();
  for (PetscInt pass = 0; pass < projection_corrections_; ++pass) correction_pass(j, pass, report);
  return report;
}

// The free surface at the new positions: its particles, its nodes (-free_surface_condition node) and,
// under the consistent operators without nodes, the particles near it.
template <int D> void IsphSolver<D>::detect_free_surface(Projection& j) {
  Particles<D>& P = disc_->particles;
  Neighbourhood<D>& nh = disc_->neighbourhood;
  const Kernel<D>& K = disc_->kernel;
  nodes_ = {};
  if (!disc_->physics.free_surface) return;
  j.surface = free_surface_model_.detect(P, nh.list(), K, true);
  if (j.nodes) nodes_ = surface_nodes(P, nh, K, j.surface, 0.5 * disc_->dx);
  if (j.consistent && !j.nodes)
    j.near_surface = near_free_surface(P, nh.list(), K, surface_flags_with_ghosts(j.surface, P, nh));
  j.surface_flags = &j.surface;
}

// The source div u* / tau, less the part of u^n's divergence below the particle scale.
template <int D>
std::vector<double> IsphSolver<D>::ppe_source(const std::vector<Vector<D>>& u_star, const Projection& j) const {
  const Particles<D>& P = disc_->particles;
  const double tau = j.tau;
  // Scale separation where a free surface cuts the support: with p = 0 on the surface particles,
  // nothing (their rows ignore the source); with surface nodes, the surface particles' rows take it,
  // and their particle-scale noise divided by tau, every step, made violent flows blow up sooner at
  // a smaller step (docs/verification/free_surface.md, "The causes, and how each was found"). The
  // average over the fluid part of the support separates it there.
  const bool average_cut = j.nodes;
  // The velocity u^n = P.v that the last projection made divergence-free has, at the particles' new
  // positions, a particle-scale divergence (div u^n minus its kernel average) that the projection
  // cannot remove: its Laplacian is not the divergence of its gradient on that scale. In the source
  // div u* / tau all of it is divided by tau, every step, and becomes a pressure noise that grows as
  // 1/dt (docs/verification/taylor_green.md, "ISPH's time error"). -ppe_particle_divergence_rate R keeps a fraction
  // R U tau / h of it instead, so that below the step with R U tau = h it is removed at a rate per
  // unit time; the step's own change of u keeps all of its divergence.
  const double kept = particle_divergence_rate_ * disc_->physics.U * tau / disc_->kernel.h();  // at least 1: all
  const bool remove_particle_scale = particle_divergence_rate_ >= 0 && solves_ > 0 && kept < 1.0;
  // The walls' pressure rows carry the hydrostatic head (Adami et al. 2012), the normal pressure
  // gradient that holds the fluid against gravity. Seen at rest by the source, the walls would count
  // the closing kick's gravity increment tau g as a compression too, and the fluid's weight twice,
  // which pushes still water up (docs/verification/free_surface.md, "The causes, and how each was
  // found"). So in the source the walls move with tau g.
  // div u* and, for the particle-scale part below, div u^n: one pass over the pairs for both.
  std::vector<std::vector<double>> divergences = remove_particle_scale
                                                     ? ppe_divergences({&u_star, &P.v}, j.near_surface, tau)
                                                     : ppe_divergences({&u_star}, j.near_surface, tau);
  std::vector<double> source = std::move(divergences[0]);
  if (remove_particle_scale) {
    std::vector<double>& div_u = divergences[1];  // its ghost values are filled for the average
    const KernelAverage<double> resolved =
        kernel_average_in_fluid(P, disc_->neighbourhood, disc_->kernel, div_u, j.surface_flags, average_cut);
    for (std::size_t i = 0; i < P.n_owned; ++i) source[i] -= (1.0 - kept) * (div_u[i] - resolved.average[i]);
  }
  relax_number_density(source, j);
  for (double& s : source) s /= tau;
  return source;
}

// -ppe_density_relaxation R: the projection asks for the divergence (theta - 1) r instead of zero, theta
// the number density's ratio to a lattice's (its kernel sum over the particles' volumes m / rho0 against
// the lattice's sum), r = R U / h at most 1 / tau: expanded fluid is drawn together over 1 / r, as in
// density-invariant ISPH (Asai et al. 2012). Only where the support is whole: not on or beside the
// free surface, where the kernel sum is cut.
template <int D> void IsphSolver<D>::relax_number_density(std::vector<double>& source, const Projection& j) const {
  if (density_relaxation_ <= 0) return;
  const Particles<D>& P = disc_->particles;
  const Kernel<D>& K = disc_->kernel;
  const double rho0 = disc_->physics.rho0;
  const double rate = std::min(density_relaxation_ * disc_->physics.U / K.h(), 1.0 / j.tau);
  const std::vector<double> flags = j.surface_flags ? surface_flags_with_ghosts(j.surface, P, disc_->neighbourhood)
                                                    : std::vector<double>(P.size(), 0.0);
  struct Sum {
    double volume = 0.0;
    bool cut = false;
  };
  const std::vector<Sum> sums =
      sum_over_pairs(P, disc_->neighbourhood.list(), K, Sum{}, [&](Sum& s, int, int b, const PairGeometry<D>& g) {
        s.volume += P.m[b] / rho0 * g.W;
        s.cut |= flags[b] != 0.0;
      });
  const double lattice = lattice_kernel_sum(K, disc_->dx);
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    if (P.kind[i] != kFluid || flags[i] != 0.0 || sums[i].cut) continue;
    const double theta = (sums[i].volume + P.m[i] / rho0 * K.W(0.0)) / lattice;
    source[i] -= (theta - 1.0) * rate;
  }
}

// -ppe_wall_impact: the velocities and wall normals of the walls' impact term.
template <int D> void IsphSolver<D>::prepare_wall_impact(const std::vector<Vector<D>>& u_star, Projection& j) {
  const Particles<D>& P = disc_->particles;
  const NeighbourList<D>& list = disc_->neighbourhood.list();
  j.predicted = u_star;
  for (std::size_t i = 0; i < P.size(); ++i)
    if (P.kind[i] != kFluid) j.predicted[i] = P.v[i];
  j.wall_normals = disc_->walls->normals(P, disc_->neighbourhood, disc_->kernel);
  // An impact is a free surface meeting a wall. Fluid already against a wall moves along it, and the
  // term on its small normal velocity (zero at the wall, O(dx) at the first particles) damps smooth
  // flows along walls (docs/verification/free_surface.md, the standing wave).
  j.impacting = disc_->physics.free_surface ? surface_flags_with_ghosts(j.surface, P, disc_->neighbourhood)
                                            : std::vector<double>(P.size(), 1.0);
  check_ghosts(list, j.predicted, "the impact term's velocity");
}

// The rows that hold a pressure: with surface nodes, p = 0 only where a particle has none (a sheet or
// a drop too thin for one, SurfaceNodes::splash, or a particle with no fluid neighbour and no node:
// alone on a wall, a node fixes its pressure level); outlets hold theirs.
template <int D> void IsphSolver<D>::set_dirichlet_rows(Projection& j) {
  Particles<D>& P = disc_->particles;
  const NeighbourList<D>& list = disc_->neighbourhood.list();
  if (j.nodes) {
    if (j.consistent) add_surface_nodes(P, list, disc_->kernel, nodes_, j.corrections);
    j.dirichlet = isolated_fluid_particles(P, list, disc_->kernel);
    for (std::size_t i = 0; i < P.n_owned; ++i)
      j.dirichlet[i] = nodes_.is_splash(i) || (j.dirichlet[i] && !nodes_.has(i));
  }
  if (!j.nodes && j.surface_flags && disc_->open.has_outlet()) j.dirichlet = j.surface;
  j.outlets = disc_->open.mark_outlets(P, j.dirichlet);
  disc_->open.hold_outlet_pressure(P, [this](double p) { return density_at_pressure(p); });
}

template <int D> void IsphSolver<D>::assemble(Projection& j) {
  const WallImpact<D> impact{&j.predicted, &j.wall_normals, &j.impacting, j.tau};
  ppe_.assemble(disc_->particles, disc_->neighbourhood, disc_->kernel, disc_->physics.gravity,
                j.nodes || j.outlets ? &j.dirichlet : j.surface_flags, j.consistent ? &j.corrections : nullptr,
                j.nodes ? &nodes_ : nullptr, wall_impact_ ? &impact : nullptr,
                j.wall_acceleration.empty() ? nullptr : &j.wall_acceleration);
}

// Solves for the pressure. A free surface holds no tension: a surface particle that the solve puts
// under tension (p < 0) is being pulled away from the fluid. It is let go (p = 0 on it) and the system
// solved again, at most twice a step. Held, such particles were sucked into the walls they slid along
// (a dam break's column corner, left behind on the wall by the no-slip condition).
template <int D> StepReport IsphSolver<D>::solve_releasing_tension(const std::vector<double>& source, Projection& j) {
  Particles<D>& P = disc_->particles;
  auto solve = [&](bool warm_start) {
    const StepReport r = ppe_.solve(source, P.m, P.p, warm_start);
    P.written(P.p);
    return r;
  };
  // The first solve starts from zero: the case's initial pressure is not the projection's.
  StepReport report = solve(solves_ > 0);
  constexpr int max_release_passes = 2;
  for (int pass = 0; pass < max_release_passes && j.nodes; ++pass) {
    int released = 0;
    for (std::size_t i = 0; i < P.n_owned; ++i)
      if (nodes_.has(i) && !j.dirichlet[i] && P.p[i] < 0.0) j.dirichlet[i] = 1, released = 1;
    MPI_Allreduce(MPI_IN_PLACE, &released, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
    if (!released) break;
    assemble(j);
    const StepReport again = solve(true);
    report.linear_iterations += again.linear_iterations;
    report.linear_residual = again.linear_residual, report.linear_reason = again.linear_reason;
  }
  return report;
}

// A correction pass: u^{n+1} keeps the divergence tau (L - D G) psi (isph_solver.hpp). Its kernel
// average is the resolved part, which a second solve with the same matrix (the preconditioner is
// reused) removes up to the relative size of L - D G again; the particle-scale rest is what no
// projection removes, and dividing it by tau once more would add the 1/dt pressure noise.
template <int D> void IsphSolver<D>::correction_pass(const Projection& j, PetscInt pass, StepReport& report) {
  Particles<D>& P = disc_->particles;
  Neighbourhood<D>& nh = disc_->neighbourhood;
  const double tau = j.tau;
  LogEventScope log_pass_source(ppe_assembly_event());
  std::vector<double> remaining = ppe_divergences({&P.v}, j.near_surface, 0.0)[0];
  std::vector<double> increment_source =
      kernel_average_in_fluid(P, nh, disc_->kernel, remaining, j.surface_flags, j.nodes).average;
  for (double& s : increment_source) s /= tau;
  log_pass_source.end();
  LogEventScope log_pass_solve(ppe_solve_event());
  std::vector<double> increment(P.n_owned, 0.0);
  const StepReport pass_report = ppe_.solve(increment_source, P.m, increment, false, true);
  report.linear_iterations += pass_report.linear_iterations;
  if (pass + 1 == projection_corrections_) ppe_.release();
  log_pass_solve.end();
  const LogEventScope log_pass_correction(LogEvent::Forces);
  increment.resize(P.size());
  nh.halo().update(increment);  // step-local: refreshed by hand
  const std::vector<Vector<D>> grad_increment = pressure_gradient(increment);
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    if (P.kind[i] == kFluid) P.v[i] -= (tau / P.rho[i]) * grad_increment[i];
    P.p[i] += increment[i];
  }
  P.written(P.v), P.written(P.p);
}

// One step of the projection scheme, phase by phase (each phase is one log event, or the PPE's own).
template <int D> StepReport IsphSolver<D>::step(double dt) {
  StepState s;
  opening_kick_and_drift(dt, s);
  closing_kick_without_pressure(dt, s);
  const StepReport report = project_and_update_pressure(dt, s);
  const Particles<D>& P = disc_->particles;
  if (shifting_model_.enabled) {
    const auto before = energy_.energies(P);
    shift(dt);
    energy_.add_change(EnergyCause::Shifting, before, energy_.energies(P));
  }
  if (bound_to_walls_) bound_to_walls();
  return report;
}

// Fluid found behind a wall's face is put back on it and its velocity into the wall removed
// (src/boundary/wall_bounding.hpp): a stop that can only take kinetic energy away. The pressures move
// with nothing: the particle keeps its own.
template <int D> void IsphSolver<D>::bound_to_walls() {
  Particles<D>& P = disc_->particles;
  disc_->neighbourhood.update(P);
  const auto before = energy_.energies(P);
  bounded_ += wall_bounding_.apply(P, disc_->neighbourhood, disc_->kernel, disc_->dx, disc_->physics.rho0,
                                   disc_->walls->moving());
  energy_.add_change(EnergyCause::WallBounding, before, energy_.energies(P));
}

// Opening kick with a^n at x^n, then the drift to x^{n+1}. Before the first projection there is no
// pressure of the scheme's own (a case's initial pressure need not be one), so that step projects the
// whole dt (project_and_update_pressure).
template <int D> void IsphSolver<D>::opening_kick_and_drift(double dt, StepState& s) {
  Particles<D>& P = disc_->particles;
  Neighbourhood<D>& nh = disc_->neighbourhood;
  const Physics<D>& phys = disc_->physics;
  const std::size_t n = P.n_owned;
  nh.update(P);
  energy_.start(P);
  const LogEventScope log_forces(LogEvent::Forces);
  s.have_pressure = solves_ > 0;
  // The surface nodes at x^n, for the pressure gradient of the opening kick.
  if (phys.free_surface && surface_condition_ == SurfaceCondition::Node)
    nodes_ = surface_nodes(P, nh, disc_->kernel, free_surface_model_.detect(P, nh.list(), disc_->kernel, false),
                           0.5 * disc_->dx);
  s.acc.assign(n, Vector<D>::Zero());
  // The factors at x^n serve this one operator: gathered in its pass (one pass over the pairs, not two).
  if (phys.viscous()) s.acc = viscous_acceleration(P.v);
  s.u_start = P.v;
  if (phys.viscous()) {
    s.viscous_kick.resize(n);
    for (std::size_t i = 0; i < n; ++i) s.viscous_kick[i] = (0.5 * dt) * s.acc[i];
  }
  if (s.have_pressure) {
    const std::vector<Vector<D>> grad_p = pressure_gradient(P.p);
    for (std::size_t i = 0; i < n; ++i) s.acc[i] -= grad_p[i] / P.rho[i];
  }
  s.u_half = P.v;
  const double potential_before_drift = energy_.potential_energy(P);
  for (std::size_t i = 0; i < n; ++i) {
    if (P.kind[i] != kFluid) continue;  // walls keep their prescribed motion
    s.acc[i] += phys.gravity;
    s.u_half[i] += (0.5 * dt) * s.acc[i];
    P.x[i] += dt * s.u_half[i];  // drift
  }
  energy_.add_change(EnergyCause::Gravity, EnergyForm::Potential, potential_before_drift, energy_.potential_energy(P));
  disc_->open.drift(P, disc_->bodies.time(), dt);
  disc_->bodies.move_to(P, disc_->bodies.time() + dt);
}

// Closing kick: the non-pressure forces at x^{n+1}, the viscous one with the predicted end velocity
// u~ = u^{n+1/2} + dt/2 a^n (as the explicit schemes do), giving u*, which the projection corrects.
// The consistent Laplacian's factors at x^{n+1} serve the viscous term and the PPE: gathered in the
// viscous term's pass where there is one, which saves a pass (docs/performance.md, "Design
// measurements"), else in a pass of their own.
template <int D> void IsphSolver<D>::closing_kick_without_pressure(double dt, StepState& s) {
  Particles<D>& P = disc_->particles;
  Neighbourhood<D>& nh = disc_->neighbourhood;
  const Physics<D>& phys = disc_->physics;
  const std::size_t n = P.n_owned;
  auto fluid = [&](std::size_t i) { return P.kind[i] == kFluid; };
  nh.update(P);
  nh.halo().update(s.u_half);  // step-local: refreshed by hand
  const bool consistent = operators_ == OperatorSet::Consistent;
  const LogEventScope log_forces(LogEvent::Forces);
  s.u_star = s.u_half;
  if (phys.viscous()) {
    std::vector<Vector<D>> u_pred = s.u_half;
    for (std::size_t i = 0; i < n; ++i)
      if (fluid(i)) u_pred[i] += (0.5 * dt) * s.acc[i];
    nh.halo().update(u_pred);  // step-local: refreshed by hand
    const std::vector<Vector<D>> visc = viscous_acceleration(u_pred, consistent ? &s.corrections : nullptr);
    for (std::size_t i = 0; i < n; ++i)
      if (fluid(i)) s.u_star[i] += (0.5 * dt) * visc[i], s.viscous_kick[i] += (0.5 * dt) * visc[i];
  }
  for (std::size_t i = 0; i < n; ++i)
    if (fluid(i)) s.u_star[i] += (0.5 * dt) * phys.gravity;
  if (consistent && !phys.viscous()) s.corrections = laplacian_corrections_if_used();
  // Spent: freed before the pressure system is built, where the step's memory peaks.
  s.acc = {}, s.u_half = {};
}

// The projection of u*, then the step's pressure: P.p holds psi after it, turned into the step's mean
// pressure and its extrapolation to t^{n+1}.
template <int D> StepReport IsphSolver<D>::project_and_update_pressure(double dt, StepState& s) {
  Particles<D>& P = disc_->particles;
  const std::size_t n = P.n_owned;
  disc_->neighbourhood.halo().update(s.u_star);  // step-local: refreshed by hand
  const std::vector<double> p_start(P.p.begin(), P.p.begin() + n);
  const StepReport report = project(s.u_star, s.have_pressure ? 0.5 * dt : dt, std::move(s.corrections));
  credit_velocity_update(dt, s);
  std::vector<double>& mean_pressure = P.fields[mean_pressure_];
  for (std::size_t i = 0; i < n; ++i) {
    if (P.kind[i] == kOutlet) {  // its own pressure, whatever it held as fluid
      P.p[i] = mean_pressure[i] = disc_->open.boundary_of(P, i)->pressure_at(P.x[i]);
      continue;
    }
    const double mean = s.have_pressure ? 0.5 * (p_start[i] + P.p[i]) : P.p[i];
    P.p[i] = s.have_pressure ? mean + 0.5 * (mean - mean_pressure[i]) : mean;
    mean_pressure[i] = mean;
  }
  P.written(P.p), P.written(mean_pressure);
  return report;
}

// The step's velocity update u^n -> u^{n+1} credited to its causes as one update (energy_budget.hpp):
// gravity's kicks and the pressure that holds the fluid up act in separate stages, and credited stage
// by stage each would be credited with an O(dt) share (|g dt / 2|^2 / 2 a kick) that the other takes back.
// The pressure's part is what the others leave: the opening kick's gradient and the projection.
template <int D> void IsphSolver<D>::credit_velocity_update(double dt, const StepState& s) {
  const Particles<D>& P = disc_->particles;
  const std::size_t n = P.n_owned;
  const std::vector<Vector<D>> gravity(n, dt * energy_.template potential_gravity<D>()),
      forcing(n, dt * energy_.template forcing_gravity<D>());
  const std::vector<Vector<D>> none(s.viscous_kick.empty() ? n : 0, Vector<D>::Zero());
  const std::vector<Vector<D>>& viscous = s.viscous_kick.empty() ? none : s.viscous_kick;
  std::vector<Vector<D>> pressure(n);
  for (std::size_t i = 0; i < n; ++i) pressure[i] = P.v[i] - s.u_start[i] - viscous[i] - gravity[i] - forcing[i];
  energy_.add_update(P, s.u_start,
                     {{EnergyCause::Gravity, 1.0, &gravity},
                      {EnergyCause::BodyForce, 1.0, &forcing},
                      {EnergyCause::Viscous, 1.0, &viscous},
                      {EnergyCause::Pressure, 1.0, &pressure}});
}

template <int D> void IsphSolver<D>::shift(double dt) {
  Particles<D>& P = disc_->particles;
  Neighbourhood<D>& nh = disc_->neighbourhood;
  const Kernel<D>& K = disc_->kernel;
  nh.update(P);  // shifting works on the new positions
  ShiftBoundary<D> boundary;
  if (disc_->physics.free_surface)
    boundary = free_surface_model_.shift_boundary(P, nh, K, free_surface_model_.detect(P, nh.list(), K, false));
  // The pressures move with the particles too: the next opening kick and extrapolation use them.
  std::vector<double>& mean_pressure = P.fields[mean_pressure_];
  shift_particles(P, nh, K, shifting_model_, disc_->dx, largest_speed(P), dt, {&P.p, &mean_pressure},
                  disc_->physics.free_surface ? &boundary : nullptr);
}

template class IsphSolver<1>;
template class IsphSolver<2>;
template class IsphSolver<3>;

}  // namespace sph
