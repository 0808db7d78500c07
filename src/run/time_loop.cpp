#include "src/run/time_loop_detail.hpp"

namespace sph {

namespace time_loop_detail {

// Moves each owned fluid particle by a random amount in [-amplitude, amplitude] along each axis, drawn
// from the seed and its permanent id alone (the same moves on any rank count): an ensemble of starts
// that differ by round-off tells whether round-off moves the answer (-start_perturbation).
template <int D> void perturb_fluid(Particles<D>& P, double amplitude, std::uint64_t seed) {
  auto splitmix = [](std::uint64_t z) {
    z += 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  };
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    if (P.kind[i] != kFluid) continue;
    for (int a = 0; a < D; ++a) {
      const std::uint64_t r = splitmix(splitmix(seed) ^ (static_cast<std::uint64_t>(P.id[i]) * D + a));
      const double unit = static_cast<double>(r >> 11) * 0x1.0p-53;  // [0, 1)
      P.x[i][a] += amplitude * (2.0 * unit - 1.0);
    }
  }
}

template <int D> TimeLoop<D>::TimeLoop(const RunParts<D>& run)
    : run_(run),
      opt_(run.control),
      case_(run.run_case),
      solver_(run.solver),
      identity_(run_identity(run.case_name, run.solver_name, D, run.run_case.parameters())),
      resumed_run_(resumed_run_header()),
      numerics_changed_(checked_restart()),
      memory_(run.solver.bytes_per_particle(), run.solver_name, run.run_case.minimum_particles()),
      s_(run.run_case, run.kernel, run.control.skin >= 0 ? run.control.skin : run.solver.neighbour_skin()),
      checkpoint_path_(run.output_dir + "/checkpoint.bin"),
      steady_(run.control.steady_tol),
      check_neighbours_(s_.disc.physics.free_surface, solver_.courant_option()) {
  memory_.check_scene(s_.P.n_owned);
  const double wall = case_.wall_thickness(), support = s_.kernel.support_radius();
  if (wall > 0 && wall < support * (1 - 1e-12))
    throw Error(case_.thin_walls(wall / case_.spacing(), support / case_.spacing()));
  if (!opt_.restarting() && opt_.start_perturbation > 0)
    perturb_fluid(s_.P, opt_.start_perturbation * case_.spacing(), static_cast<std::uint64_t>(opt_.start_seed));
  s_.disc.open = OpenBoundaries<D>(case_.open_boundaries());
  s_.disc.open.start_ids(s_.P);
  solver_.setup(s_.disc);
  place_ = s_.P.fields.declare_scalar("storage_index", kCarried | kOptional, s_.P.size());
  x_at_build_ = s_.P.fields.declare_vector("x_at_build", kCarried | kOptional, s_.P.size());
  if (opt_.restarting()) resume();
  // Bodies with prescribed motion start at the run's time, with their velocity there.
  std::vector<FreeBody<D>> free = case_.free_bodies();
  const double added = opt_.free_body_added_mass >= 0 ? opt_.free_body_added_mass : solver_.free_body_added_mass();
  for (FreeBody<D>& f : free)
    if (f.active) f.added_mass_ratio = added * s_.disc.physics.rho0 * f.volume / f.mass;
  s_.disc.bodies = MovingBodies<D>(case_.body_motions(), case_.body_of_particles(), resumed_.t,
                                   case_.free_slip_of_particles(), std::move(free), case_.wall_pressure_of_particles());
  if (opt_.restarting() && resumed_run_.contains("free_bodies")) {
    s_.disc.bodies.restore(resumed_run_["free_bodies"].value("state", nlohmann::json::array()));
    contact_step_ = resumed_run_["free_bodies"].value("contact_step", 0.0);
  }
  s_.disc.bodies.carry_plates(s_.domain.screens);
  // A restart's lists were screened with the plates where the scene laid them: again, where they are.
  if (opt_.restarting() && s_.domain.screens) s_.nh.refresh(s_.P);
  s_.disc.bodies.move_to(s_.P, resumed_.t);
  s_.disc.open.prescribe(s_.P, resumed_.t);
  check_initial_state(s_.P, resumed_.t);
  if (opt_.dt > 0 && !opt_.dt_force && opt_.dt > solver_.stable_dt())
    throw Error(dt_above_limit(solver_.stable_dt(), resumed_.t) +
                "; lower -dt (-dt 0 follows the limit) or pass -dt_force 1 to run it anyway");
}

// A step so small that the run cannot end (-cfl 1e-30 gave an ETA of 1e27 s) is refused at the first
// step, before anything is spent on it, naming what made it small: -dt, a Courant number the user
// lowered, or else the flow's own speed (a scene's velocity in the wrong units).
template <int D> void TimeLoop<D>::refuse_endless_run(double dt) const {
  constexpr double kMostSteps = 1e9;
  const double steps = (opt_.t_end - t_) / dt;
  if (steps <= kMostSteps) return;
  PetscBool courant_given = PETSC_FALSE;
  SPH_PETSC(PetscOptionsHasName(nullptr, nullptr, solver_.courant_option().c_str(), &courant_given));
  double fastest = 0.0;
  for (std::size_t i = 0; i < s_.P.n_owned; ++i) fastest = std::max(fastest, double(s_.P.v[i].stableNorm()));
  MPI_Allreduce(MPI_IN_PLACE, &fastest, 1, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
  std::ostringstream msg;
  msg << "the time step " << dt << " leaves " << steps << " steps to -t_end " << opt_.t_end << " (more than "
      << kMostSteps << "): ";
  if (opt_.dt > 0) msg << "-dt is far too small; raise it or leave it out";
  else if (courant_given) msg << solver_.courant_option() << " is far too small; raise it";
  else
    msg << "the flow's speed sets it (the fastest particle moves at " << fastest << " against a spacing of "
        << case_.spacing() << "), far too fast for the scene's size and -t_end: check the initial velocities "
        << "and their units (or -c0)";
  throw Error(msg.str());
}

template <int D> std::string TimeLoop<D>::dt_above_limit(double stable, double t_now) const {
  std::ostringstream msg;
  msg << "-dt " << opt_.dt << " exceeds the scheme's stability limit " << stable << " at t = " << t_now;
  return msg.str();
}

// Re-orders and re-balances the particles (with the solver's per-particle state) along the curve and
// rebuilds the neighbourhood: the canonical state, which depends only on the particles.
template <int D> void TimeLoop<D>::repartition() {
  s_.imbalance = partition_along_curve(s_.P, s_.domain);
  ++partitions_;
  s_.nh.update(s_.P, true);
}

template <int D> void TimeLoop<D>::run() {
  open_outputs();
  describe_run();
  set_start_state();
  // Free bodies start with the load of the initial state; a restart has it from the checkpoint.
  if (s_.disc.bodies.any_free() && !opt_.restarting())
    load_free_bodies(
        wall_groups_->forces(s_.P, s_.nh, s_.kernel, s_.disc.physics, s_.disc.bodies, s_.disc.walls.get()));
  try {
    const TimeLoopLogStage log_stage;
    while (!time_reached(t_, opt_.t_end) && (opt_.max_steps < 0 || step_ < opt_.max_steps) && !steady_.reached()) {
      advance();
      write_due_outputs();
      if ((interrupted_ = interrupt_requested())) break;  // all ranks see the same answer
    }
    if (interrupted_) {
      // Everything needed to look at the state reached and to resume it.
      if (last_frame_t_ < t_) write_frame(), last_frame_t_ = t_;
      if (last_checkpoint_step_ != step_) write_state("interrupted (" + signal_name(interrupted_) + ")");
    } else if (!time_reached(t_, opt_.t_end)) {
      stop_early();
    }
  } catch (const OptionError&) {
    throw;  // a mistake in the command line, not a failed run
  } catch (const Error& e) {
    fail(e);
  }
  progress_->done(step_, t_);
  if (interrupted_) stop_interrupted();
  const LogEventScope log_output(LogEvent::Output);
  if (opt_.steady_tol > 0) summary_["steady_state_reached"] = steady_.reached();
  case_.write_outputs(s_.P, t_, run_.output_dir);
  if (last_frame_t_ < t_) write_frame();  // e.g. stopped at steady state between frames
  finish("completed", "");
}

// The state the loop starts from, its first frame, and the reference values the health checks compare with.
template <int D> void TimeLoop<D>::set_start_state() {
  initial_ = totals(s_.P);
  t_ = resumed_.t;
  step_ = resumed_.step;
  failing_step_ = step_ + 1;
  stats_.from_json(resumed_run_.value("ksp_statistics", nlohmann::json()));
  steady_.from_json(resumed_run_.value("steady_state_window", nlohmann::json()));
  if (resumed_run_.contains("removed_fluid")) {
    removed_.count = resumed_run_["removed_fluid"].value("particles", 0LL);
    removed_.mass = resumed_run_["removed_fluid"].value("mass", 0.0);
  }
  history_ = resumed_run_.value("history", nlohmann::json::array());
  if (opt_.restarting()) case_.restore_accumulated_state(resumed_run_.value("case_state", nlohmann::json()));
  progress_.emplace(opt_.progress, opt_.t_end);
  const double frame_interval = opt_.output_interval > 0 ? opt_.output_interval : opt_.t_end;
  frames_.emplace(frame_interval, t_);
  checkpoints_.emplace(opt_.checkpoint_interval < 0 ? frame_interval : opt_.checkpoint_interval, t_);
  if (!opt_.restarting()) write_frame();
  last_frame_t_ = t_;
  const double U = s_.disc.physics.U;
  ke_bound_ = kBlowUpKineticEnergy * 0.5 * fluid_mass(s_.P) * U * U;
  check_neighbours_(s_.P, s_.nh.list(), s_.nh.support_radius());  // the reference counts
  loop_start_ = Clock::now();
}

// One step, its health checks and its timeseries row.
template <int D> void TimeLoop<D>::advance() {
  double stable = solver_.stable_dt();
  if (contact_step_ > 0.0) stable = std::min(stable, contact_step_);  // a free body touches a solid
  // A free body moves at most a quarter of h a step, as the fluid's CFL limits keep the fluid.
  if (s_.disc.bodies.any_free()) stable = std::min(stable, s_.disc.bodies.free_step(s_.kernel.h(), 0.25));
  double dt = opt_.dt > 0 ? opt_.dt : stable;
  if (opt_.dt > stable) warn_dt(stable);
  // -output_times exact: the steps to the next frame evened out as those to t_end are.
  const double target = opt_.exact_output_times ? std::min(opt_.t_end, frames_->next()) : opt_.t_end;
  dt = step_to_end(t_, target, dt);
  if (step_ == resumed_.step) refuse_endless_run(dt);
  LogEventScope log_step(LogEvent::Step);
  failing_step_ = step_ + 1;
  s_.disc.bodies.kick(s_.P, 0.5 * dt);  // free bodies: the opening kick, with the load at the step's start
  const StepReport report = solver_.step(dt);
  log_step.end();
  t_ += dt;
  ++step_;
  failing_step_ = step_;  // what fails from here on (checks, output) belongs to the step just made
  stats_.add(report);
  if (step_ == resumed_.step + 1 && run_.after_first_step) run_.after_first_step();
  LogEventScope log_diagnostics(LogEvent::Diagnostics);
  if (s_.disc.open.any()) exchange_open_boundaries();
  if (opt_.box_exit != 0 && fluid_outside(s_.P, s_.domain)) remove_escaped_fluid();
  check_health(s_.P, s_.domain, ke_bound_, solver_.courant_option(), opt_.box_exit == 2);
  check_bodies();
  check_neighbours_(s_.P, s_.nh.list(), s_.nh.support_radius());
  if (opt_.partition_interval > 0 && step_ % opt_.partition_interval == 0) repartition();

  const Totals<D> tot = totals(s_.P);
  steady_.add(t_, tot.kinetic_energy);
  std::vector<double> row = {double(step_), t_, dt, tot.kinetic_energy};
  for (int a = 0; a < D; ++a) row.push_back(tot.momentum[a]);
  row.push_back(report.linear_iterations);
  row.push_back(report.linear_reason);
  case_.accumulate(s_.P, t_, dt);
  for (const auto& e : case_.errors(s_.P, t_)) row.push_back(e.second);
  if (surface_column_) row.push_back(fluid_share(s_.P, *s_.P.fields.find_scalar("free_surface", kWritten)));
  if (walls_column_) row.push_back(static_cast<double>(fluid_in_walls(s_.P, s_.nh.list(), case_.spacing())));
  if (counts_removed_fluid()) row.push_back(static_cast<double>(removed_.count));
  if (s_.disc.open.any()) {
    const OpenBoundaryFlux& f = s_.disc.open.flux();
    row.insert(row.end(), {f.in_mass, f.out_mass, fluid_mass(s_.P)});
  }
  if (const EnergyBudget* budget = solver_.energy_budget()) {
    const std::vector<double> energy = budget->row(budget->totals(s_.P));
    row.insert(row.end(), energy.begin(), energy.end());
  }
  if (wall_groups_) {
    const std::vector<GroupForce<D>> F =
        wall_groups_->forces(s_.P, s_.nh, s_.kernel, s_.disc.physics, s_.disc.bodies, s_.disc.walls.get());
    faces_t_ = t_;  // the frames' surface loads are these
    const std::vector<double> forces = wall_groups_->row(F);
    row.insert(row.end(), forces.begin(), forces.end());
    if (s_.disc.bodies.any_free()) {  // the free bodies' closing kick, with the load at the step's end
      load_free_bodies(F);
      s_.disc.bodies.kick(s_.P, 0.5 * dt);
    }
  }
  const std::vector<double> free = free_body_row(s_.disc.bodies);
  row.insert(row.end(), free.begin(), free.end());
  if (!probes_.empty()) {
    const std::vector<double> probes = probe_pressures(s_.P, s_.domain, s_.kernel, probes_);
    row.insert(row.end(), probes.begin(), probes.end());
  }
  series_->row(row);
  log_diagnostics.end();
  progress_->update(step_, t_, dt, report.linear_iterations);
}

// The open boundaries' exchange after a step (src/boundary/open_boundaries.hpp): the energy the fluid
// brings in and takes out credited to them; the lists rebuilt when a particle came, went or changed kind.
template <int D> void TimeLoop<D>::exchange_open_boundaries() {
  EnergyBudget* budget = solver_.energy_budget();
  const auto before = budget ? budget->energies(s_.P) : std::array<double, EnergyBudget::kForms>{};
  const bool changed = s_.disc.open.exchange(s_.P, t_, [&](double p) { return solver_.density_at_pressure(p); });
  if (budget && changed) budget->add_change(EnergyCause::OpenBoundaries, before, budget->energies(s_.P));
  s_.nh.update(s_.P, changed);
  s_.disc.open.extrapolate_outlet_velocity(s_.P, s_.nh.list(), s_.kernel);
  s_.nh.halo().update(s_.P.v);
}

// Fluid outside the box goes (-box_exit auto: unless it went through a wall, which the health check
// then stops at), counted, its energy credited to the budget, and said in a warning line.
template <int D> void TimeLoop<D>::remove_escaped_fluid() {
  EnergyBudget* budget = solver_.energy_budget();
  const auto before = budget ? budget->energies(s_.P) : std::array<double, EnergyBudget::kForms>{};
  const RemovedFluid gone = remove_fluid_outside(s_.P, s_.nh.list(), s_.domain, case_.spacing(), opt_.box_exit == 1);
  if (gone.count == 0) return;
  removed_.count += gone.count, removed_.mass += gone.mass;
  if (budget) budget->add_change(EnergyCause::RemovedFluid, before, budget->energies(s_.P));
  s_.nh.update(s_.P, true);
  // A splash may throw out many: the first few removals are said, the rest counted in timeseries.csv.
  constexpr int kWarnings = 5;
  if (++removal_events_ > kWarnings) return;
  std::ostringstream w;
  w << "step " << step_ << " (t = " << t_ << "): " << gone.count << " fluid particle" << (gone.count > 1 ? "s" : "")
    << " left the box over an open side and " << (gone.count > 1 ? "were" : "was") << " taken out of the run (mass "
    << gone.mass << "; " << removed_.count << " so far, timeseries.csv's removed_fluid"
    << (removal_events_ == kWarnings ? "; further removals are not said here" : "") << ")";
  PetscFPrintf(PETSC_COMM_WORLD, stderr, "sph: warning: %s\n", w.str().c_str());
}

// A -dt above the stability limit is refused at the start unless -dt_force; a forced one, or the limit
// falling below -dt later, is a warning, printed once and kept in summary.json.
template <int D> void TimeLoop<D>::warn_dt(double stable) {
  if (warned_dt_) return;
  const std::string w = dt_above_limit(stable, t_) + "; the run may blow up";
  PetscFPrintf(PETSC_COMM_WORLD, stderr, "sph: warning: %s\n", w.c_str());
  summary_["warnings"].push_back(w);
  warned_dt_ = true;
}

// A body carried out of the box stops the run; one driven into a fixed wall is said once, in a warning
// kept in summary.json (src/run/body_checks.hpp).
template <int D> void TimeLoop<D>::check_bodies() {
  if (!s_.disc.bodies.any()) return;
  const std::vector<std::string> names = case_.body_names();
  check_bodies_in_box(s_.P, s_.domain, s_.disc.bodies, names, t_);
  const std::vector<int> inside = bodies_in_fixed_walls(s_.P, s_.nh.list(), s_.disc.bodies, case_.spacing());
  warned_in_walls_.resize(inside.size(), 0);
  for (std::size_t b = 0; b < inside.size(); ++b) {
    if (!inside[b] || warned_in_walls_[b]) continue;
    std::ostringstream w;
    w << "step " << step_ << " (t = " << t_ << "): body " << body_label(names, static_cast<int>(b))
      << " has entered a fixed wall (particles closer than half a spacing): its prescribed motion drives it "
         "through the wall; change the motion or the walls";
    PetscFPrintf(PETSC_COMM_WORLD, stderr, "sph: warning: %s\n", w.str().c_str());
    summary_["warnings"].push_back(w.str());
    warned_in_walls_[b] = 1;
  }
}

// Each member is compiled once, in the file that defines it, for 1, 2 and 3 dimensions.
#define SPH_INSTANTIATE_TIME_LOOP(D)                                                   \
  template TimeLoop<D>::TimeLoop(const RunParts<D>& run);                              \
  template void TimeLoop<D>::refuse_endless_run(double dt) const;                      \
  template std::string TimeLoop<D>::dt_above_limit(double stable, double t_now) const; \
  template void TimeLoop<D>::repartition();                                            \
  template void TimeLoop<D>::run();                                                    \
  template void TimeLoop<D>::set_start_state();                                        \
  template void TimeLoop<D>::advance();                                                \
  template void TimeLoop<D>::exchange_open_boundaries();                               \
  template void TimeLoop<D>::remove_escaped_fluid();                                   \
  template void TimeLoop<D>::warn_dt(double stable);                                   \
  template void TimeLoop<D>::check_bodies();
SPH_INSTANTIATE_TIME_LOOP(1)
SPH_INSTANTIATE_TIME_LOOP(2)
SPH_INSTANTIATE_TIME_LOOP(3)
#undef SPH_INSTANTIATE_TIME_LOOP

}  // namespace time_loop_detail

template <int D> void run_time_loop(const RunParts<D>& run) { time_loop_detail::TimeLoop<D>(run).run(); }

template void run_time_loop<1>(const RunParts<1>&);
template void run_time_loop<2>(const RunParts<2>&);
template void run_time_loop<3>(const RunParts<3>&);

}  // namespace sph
