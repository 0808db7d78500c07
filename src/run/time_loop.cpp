#include "src/run/time_loop.hpp"

#include <petscsys.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <sstream>

#include "src/boundary/adami_wall.hpp"
#include "src/boundary/body_contact.hpp"
#include "src/core/log_events.hpp"
#include "src/core/options.hpp"
#include "src/io/checkpoint.hpp"
#include "src/io/csv_writer.hpp"
#include "src/io/json_file.hpp"
#include "src/io/output_dir.hpp"
#include "src/io/particle_writer.hpp"
#include "src/neighbours/partition.hpp"
#include "src/run/box_exit.hpp"
#include "src/run/diagnostics.hpp"
#include "src/run/free_body_outputs.hpp"
#include "src/run/interrupt.hpp"
#include "src/run/memory_budget.hpp"
#include "src/run/progress.hpp"
#include "src/run/provenance.hpp"
#include "src/run/run_identity.hpp"
#include "src/run/run_statistics.hpp"
#include "src/run/run_summary.hpp"
#include "src/run/schedule.hpp"
#include "src/run/wall_groups.hpp"
#include "src/sph/vorticity.hpp"

namespace sph {

namespace {
// A run has blown up when the kinetic energy exceeds this many times 1/2 M U^2 (docs/user-guide.md).
constexpr double kBlowUpKineticEnergy = 1e3;

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

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

// The particles of a run, spread along the space-filling curve, and what the solver sees of them.
template <int D> struct RunState {
  Particles<D> P;
  Domain<D> domain;
  double imbalance;  // of the last partition
  Kernel<D> kernel;
  Neighbourhood<D> nh;
  Discretisation<D> disc;

  RunState(Case<D>& run_case, const KernelChoice& choice, double skin)
      : imbalance(create(run_case)),
        kernel(choice.template make<D>(run_case.spacing())),
        nh(domain, kernel.support_radius(), skin * kernel.support_radius()),
        disc{P, nh, kernel, run_case.physics(), run_case.spacing()} {}

 private:
  double create(Case<D>& run_case) {
    run_case.create(P, domain);
    assign_global_indices(P);
    return partition_along_curve(P, domain);
  }
};

// One run, from the case's particles to summary.json. The constructor takes every input and refuses
// bad input before anything in the output directory is touched; run() then advances and writes.
template <int D> class TimeLoop {
 public:
  explicit TimeLoop(const RunParts<D>& run);
  void run();

 private:
  nlohmann::json resumed_run_header() const;
  void resume();
  std::string dt_above_limit(double stable, double t_now) const;
  void open_outputs();
  void describe_run();
  void set_start_state();
  void advance();
  void refuse_endless_run(double dt) const;
  void write_due_outputs();
  void remove_escaped_fluid();
  void exchange_open_boundaries();
  // The free bodies' accelerations from the groups' forces (body b is group b), their contact with
  // walls and other bodies, and gravity; near a contact, the next steps are held to resolve it.
  void load_free_bodies(const std::vector<GroupForce<D>>& F) {
    const double dx = case_.spacing(), g = s_.disc.physics.gravity.norm();
    const ContactLoad<D> contact = body_contact(s_.P, s_.nh.list(), s_.disc.bodies, dx, g);
    contact_step_ = contact.near ? contact_step(g, dx) : 0.0;
    std::vector<Vector<D>> force;
    std::vector<Eigen::Vector3d> moment;
    for (std::size_t b = 0; b < contact.force.size(); ++b)
      force.push_back(F[b].total() + contact.force[b]), moment.push_back(F[b].moment + contact.moment[b]);
    s_.disc.bodies.set_loads(force, moment, s_.disc.physics.gravity, contact.force);
  }
  // Whether fluid can be taken out of this run (a side of the box is not periodic, -box_exit not stop).
  bool counts_removed_fluid() const {
    bool open = false;
    for (int a = 0; a < D; ++a) open = open || !s_.domain.periodic[a];
    return opt_.box_exit != 0 && open;
  }
  void warn_dt(double stable);
  std::vector<ScalarField> frame_fields(bool derived = true);
  void write_frame(bool derived = true);
  void repartition();
  void restore_order_and_lists();
  void write_state(const std::string& why = "checkpointed");
  nlohmann::json this_segment(const std::string& status) const;
  nlohmann::json checked_restart() const;
  void stop_early();
  void finish(const std::string& status, const std::string& failure);
  [[noreturn]] void fail(const Error& e);
  [[noreturn]] void stop_interrupted();

  const RunParts<D>& run_;
  const RunControl& opt_;
  Case<D>& case_;
  Solver<D>& solver_;
  const Clock::time_point wall_start_ = Clock::now();
  // A restart must continue the run that wrote the checkpoint: refused before any work if the
  // checkpoint is damaged or was written with other options.
  const nlohmann::json identity_;
  const nlohmann::json resumed_run_;
  const nlohmann::json numerics_changed_;  // by this restart: -cfl, -dt, -ppe_ksp_*, ...
  const MemoryBudgetScope memory_;         // checked as the scene is created, before the solver allocates
  RunState<D> s_;
  long partitions_ = 1;
  // The checkpoints' record of where each particle is stored (its global index) and of the positions
  // the neighbour lists were built at: a restart on as many ranks puts both back (restore_order_and_lists).
  FieldId<double> place_;
  FieldId<Vector<D>> x_at_build_;
  CheckpointState<D> resumed_;
  const std::string checkpoint_path_;

  // Outputs, opened once the input is accepted.
  OutputDirLock dir_lock_;  // held to the end of the run
  std::optional<ParticleWriter<D>> writer_;
  std::optional<CsvWriter> series_;
  std::optional<WallGroups<D>> wall_groups_;  // timeseries.csv's force columns
  std::vector<SurfaceMesh> body_surfaces_;    // each body's, at t = 0
  std::vector<SurfaceWriter> surface_writers_;
  std::vector<std::vector<double>> vorticity_;
  std::vector<double> body_index_;  // the frames' "body" field
  nlohmann::json summary_;
  int ranks_ = 1;

  // The run's state beyond the particles.
  double t_ = 0.0;
  long step_ = 0;
  StepStats stats_;
  SteadyState steady_;
  nlohmann::json history_;  // the runs that led to the checkpoint this one resumes
  std::optional<Totals<D>> initial_;
  long last_checkpoint_step_ = -1, failing_step_ = 0;
  int interrupted_ = 0;  // the signal that stopped the run
  bool warned_dt_ = false;
  double contact_step_ = 0.0;                           // > 0: a free body is near a contact, the step held to this
  bool surface_column_ = false, walls_column_ = false;  // timeseries.csv's free_surface_share, fluid_in_walls
  RemovedFluid removed_;  // -box_exit auto or remove: the fluid taken out so far (timeseries.csv's removed_fluid)
  int removal_events_ = 0;
  double last_frame_t_ = 0.0, ke_bound_ = 0.0;
  std::optional<Progress> progress_;
  std::optional<Cadence> frames_, checkpoints_;
  NeighbourCountCheck<D> check_neighbours_;
  Clock::time_point loop_start_;
};

template <int D> TimeLoop<D>::TimeLoop(const RunParts<D>& run)
    : run_(run),
      opt_(run.control),
      case_(run.run_case),
      solver_(run.solver),
      identity_(run_identity(run.case_name, run.solver_name, D, run.run_case.parameters())),
      resumed_run_(resumed_run_header()),
      numerics_changed_(checked_restart()),
      memory_(run.solver.bytes_per_particle(), run.solver_name),
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
                                   case_.free_slip_of_particles(), std::move(free));
  if (opt_.restarting() && resumed_run_.contains("free_bodies")) {
    s_.disc.bodies.restore(resumed_run_["free_bodies"].value("state", nlohmann::json::array()));
    contact_step_ = resumed_run_["free_bodies"].value("contact_step", 0.0);
  }
  s_.disc.bodies.move_to(s_.P, resumed_.t);
  s_.disc.open.prescribe(s_.P, resumed_.t);
  check_initial_state(s_.P, resumed_.t);
  if (opt_.dt > 0 && !opt_.dt_force && opt_.dt > solver_.stable_dt())
    throw Error(dt_above_limit(solver_.stable_dt(), resumed_.t) +
                "; lower -dt (-dt 0 follows the limit) or pass -dt_force 1 to run it anyway");
}

// A restart may change the numerics of the steps to come (a smaller step to rescue a failing run):
// said at the start, recorded in the history.
template <int D> nlohmann::json TimeLoop<D>::checked_restart() const {
  if (!opt_.restarting()) return nlohmann::json::object();
  const nlohmann::json changed =
      check_same_run(resumed_run_.value("identity", nlohmann::json()), identity_, opt_.restart);
  auto text = [](const nlohmann::json& v) { return v.is_null() ? std::string("(flag)") : v.get<std::string>(); };
  for (const auto& [name, change] : changed.items())
    PetscPrintf(PETSC_COMM_WORLD, "restart: -%s %s (was %s): the numerics of the steps to come\n", name.c_str(),
                text(change["now"]).c_str(), text(change["was"]).c_str());
  return changed;
}

template <int D> nlohmann::json TimeLoop<D>::resumed_run_header() const {
  if (!opt_.restarting()) return nlohmann::json::object();
  nlohmann::json resumed = read_checkpoint_header(opt_.restart).value("run", nlohmann::json::object());
  return resumed;
}

// A restart overwrites the freshly set-up state with the checkpoint's, then puts the particles and
// the neighbour lists where the writing run had them, so that it continues bit for bit. On another
// rank count, or from a checkpoint without that record, it re-partitions along the curve instead: the
// same particles in another order, whose sums round differently.
template <int D> void TimeLoop<D>::resume() {
  resumed_ = read_checkpoint(opt_.restart, s_.P, s_.disc.open.any());
  s_.disc.open.restore(resumed_run_.value("open_boundaries", nlohmann::json()));
  // The fluid the writing run had taken out of the box (-box_exit auto or remove) goes again.
  remove_particles_if(s_.P, [&](std::size_t i) { return s_.P.kind[i] == kRemovedKind; });
  solver_.restore_scalars(resumed_.scalars);
  const nlohmann::json order = resumed_run_.value("order", nlohmann::json::object());
  PetscMPIInt ranks;
  MPI_Comm_size(PETSC_COMM_WORLD, &ranks);
  if (order.value("ranks", 0) == ranks) return restore_order_and_lists();
  const std::string why = order.contains("ranks")
                              ? std::to_string(ranks) + (ranks == 1 ? " rank" : " ranks") +
                                    ", the checkpoint was written on " + std::to_string(order["ranks"].get<int>())
                              : "the checkpoint has no record of its particles' order";
  PetscPrintf(PETSC_COMM_WORLD,
              "restart: %s: continuing from the curve's order; results match the uninterrupted run to "
              "round-off, not bitwise\n",
              why.c_str());
  repartition();
}

// The writing run's order: each particle on its rank at its place, and the lists built at the
// positions the writing run built them at (wrapped, so wrapping them again changes nothing), which
// makes the lists, the ghosts and the next rebuild's decision that run's.
template <int D> void TimeLoop<D>::restore_order_and_lists() {
  Particles<D>& P = s_.P;
  const std::vector<double>& place = P.fields[place_];
  const std::vector<GlobalIndex> gid(place.begin(), place.begin() + P.n_owned);
  s_.imbalance = restore_order(P, gid, resumed_run_.at("order").at("owned").get<std::vector<GlobalIndex>>());
  std::vector<Vector<D>>& built = P.fields[x_at_build_];
  std::swap_ranges(P.x.begin(), P.x.begin() + P.n_owned, built.begin());
  s_.nh.update(P, true);
  std::swap_ranges(P.x.begin(), P.x.begin() + P.n_owned, built.begin());
  // As an update that does not rebuild leaves them: the ghosts at the owned particles' positions,
  // the plates' screens at them.
  s_.nh.refresh(P);
}

// A step so small that the run cannot end (-cfl 1e-30 gave an ETA of 1e27 s) is refused at the first
// step, before anything is spent on it.
template <int D> void TimeLoop<D>::refuse_endless_run(double dt) const {
  constexpr double kMostSteps = 1e9;
  const double steps = (opt_.t_end - t_) / dt;
  if (steps <= kMostSteps) return;
  std::ostringstream msg;
  msg << "the time step " << dt << " leaves " << steps << " steps to -t_end " << opt_.t_end << " (more than "
      << kMostSteps << "): "
      << (opt_.dt > 0 ? std::string("-dt is far too small; raise it or leave it out")
                      : solver_.courant_option() + " is far too small; raise it");
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
    load_free_bodies(wall_groups_->forces(s_.P, s_.nh, s_.kernel, s_.disc.physics, s_.disc.bodies));
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

// Only now, with the input accepted, may an earlier run in the output directory go (-overwrite).
template <int D> void TimeLoop<D>::open_outputs() {
  const std::string& dir = run_.output_dir;
  const bool restarting = opt_.restarting();
  const bool in_place = restarting && is_in_directory(opt_.restart, dir);
  dir_lock_ = prepare_output_dir(dir, opt_.overwrite, in_place);
  writer_.emplace(dir);
  if (restarting) writer_->resume(resumed_.t);
  if (in_place) remove_frames_from(dir, "particles", writer_->frames_written());
  // Each body's surface beside the frames, moved with it.
  body_surfaces_ = case_.body_surfaces();
  const std::vector<std::string> bodies = case_.body_names();
  for (std::size_t b = 0; b < body_surfaces_.size() && b < bodies.size(); ++b) {
    surface_writers_.emplace_back(dir, bodies[b]);
    if (restarting) surface_writers_.back().resume(resumed_.t);
    if (in_place) remove_frames_from(dir, surface_writers_.back().basename(), surface_writers_.back().frames_written());
  }
  std::vector<std::string> columns = {"step", "t", "dt", "kinetic_energy"};
  for (int a = 0; a < D; ++a) columns.push_back(std::string("momentum_") + "xyz"[a]);
  columns.insert(columns.end(), {"ksp_iterations", "ksp_reason"});
  for (const auto& e : case_.errors(s_.P, 0.0)) columns.push_back(e.first);
  // Free-surface and wall health: the share of fluid particles on the surface (the scheme's flags) and
  // the fluid particles inside a wall (diagnostics.hpp).
  surface_column_ = s_.disc.physics.free_surface && s_.P.fields.find_scalar("free_surface", kWritten) != nullptr;
  walls_column_ = has_walls(s_.P);
  if (surface_column_) columns.push_back("free_surface_share");
  if (walls_column_) columns.push_back("fluid_in_walls");
  if (counts_removed_fluid()) columns.push_back("removed_fluid");
  if (s_.disc.open.any()) columns.insert(columns.end(), {"inflow_mass", "outflow_mass", "fluid_mass"});
  if (const EnergyBudget* budget = solver_.energy_budget()) {
    const std::vector<std::string> energy = budget->columns();
    columns.insert(columns.end(), energy.begin(), energy.end());
  }
  // Free bodies move by the forces: they are computed whatever -wall_forces says.
  if (walls_column_ && (opt_.wall_forces || s_.disc.bodies.any_free())) {
    wall_groups_.emplace(case_, s_.P, opt_.body_pressure_force == 0,
                         resumed_run_.value("moment_about", nlohmann::json()));
    const std::vector<std::string> forces = wall_groups_->columns();
    columns.insert(columns.end(), forces.begin(), forces.end());
  }
  const std::vector<std::string> free = free_body_columns(case_.body_names(), s_.disc.bodies);
  columns.insert(columns.end(), free.begin(), free.end());
  if (restarting) series_.emplace(dir + "/timeseries.csv", columns, 1, resumed_.t);
  else series_.emplace(dir + "/timeseries.csv", columns);
}

// What summary.json says of the run before it starts.
template <int D> void TimeLoop<D>::describe_run() {
  nlohmann::json& j = summary_;
  j["case"] = run_.case_name;
  j["solver"] = run_.solver_name;
  j["dim"] = D;
  j["n_particles"] = s_.P.n_global;
  j["dx"] = case_.spacing();
  j["kernel"] = {
      {"type", s_.kernel.name()}, {"h", s_.kernel.h()}, {"h_over_dx", run_.kernel.template resolved_h_over_dx<D>()}};
  j["t_end"] = opt_.t_end;
  j["parameters"] = case_.parameters();
  j["physics"] = s_.disc.physics.describe();
  PetscMPIInt ranks;
  MPI_Comm_size(PETSC_COMM_WORLD, &ranks);
  ranks_ = ranks;
  j["mpi_ranks"] = ranks_;
  j["threads_per_rank"] = opt_.threads;
  j["provenance"] = provenance(static_cast<int>(opt_.threads));
  if (wall_groups_) j["wall_groups"] = wall_groups_->describe();
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
  dt = step_to_end(t_, opt_.t_end, dt);
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
    const std::vector<GroupForce<D>> F = wall_groups_->forces(s_.P, s_.nh, s_.kernel, s_.disc.physics, s_.disc.bodies);
    const std::vector<double> forces = wall_groups_->row(F);
    row.insert(row.end(), forces.begin(), forces.end());
    if (s_.disc.bodies.any_free()) {  // the free bodies' closing kick, with the load at the step's end
      load_free_bodies(F);
      s_.disc.bodies.kick(s_.P, 0.5 * dt);
    }
  }
  const std::vector<double> free = free_body_row(s_.disc.bodies);
  row.insert(row.end(), free.begin(), free.end());
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

template <int D> void TimeLoop<D>::write_due_outputs() {
  if (frames_->due(t_) || time_reached(t_, opt_.t_end)) {
    const LogEventScope log_output(LogEvent::Output);
    write_frame();
    last_frame_t_ = t_;
    frames_->advance(t_);
  }
  if (checkpoints_->due(t_)) {
    write_state();
    checkpoints_->advance(t_);
  }
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

// A particle frame, and each body's surface where the body is now.
template <int D> void TimeLoop<D>::write_frame(bool derived) {
  writer_->write(s_.P, t_, frame_fields(derived));
  const std::vector<PrescribedMotion<D>> motions = case_.body_motions();
  for (std::size_t b = 0; b < surface_writers_.size(); ++b) {
    SurfaceMesh surface = body_surfaces_[b];
    const FreeBody<D>* free = s_.disc.bodies.free_body(b);
    if (free || (b < motions.size() && motions[b].moves()))
      for (auto& x : surface.points) {
        Vector<D> p;
        for (int a = 0; a < D; ++a) p[a] = x[a];
        p = free ? free->placed(p) : motions[b].moved(p, 0.0, t_);
        for (int a = 0; a < D; ++a) x[a] = p[a];
      }
    surface_writers_[b].write(surface, t_);
  }
}

// The solver's own fields and the optional ones, for every frame.
template <int D> std::vector<ScalarField> TimeLoop<D>::frame_fields(bool derived) {
  std::vector<ScalarField> fields = s_.P.fields.scalars_with(kWritten);
  // Which body each particle belongs to (its index in summary.json's parameters.bodies; -1: none), so
  // that ParaView can tell the bodies apart from the walls and from each other.
  if (!case_.body_names().empty()) {
    body_index_.assign(s_.P.n_owned, -1.0);
    for (std::size_t i = 0; i < s_.P.n_owned; ++i) body_index_[i] = s_.disc.bodies.body_of(s_.P, i);
    fields.push_back({"body", &body_index_});
  }
  if (!opt_.vorticity_output || !derived) return fields;
  // The ghosts' velocities and positions as the step left the owned ones, in a neighbourhood of its
  // own: the run's lists, halo and (periodic) positions stay as they were, so the frames' extra fields
  // change no result, bitwise (tests/cli/output_fields.sh).
  Particles<D> P = s_.P;
  Neighbourhood<D> nh(s_.nh.domain(), s_.nh.support_radius(), 0.0);
  nh.update(P, true);
  vorticity_ = fluid_vorticity(P, nh.list(), s_.kernel);
  const char* names[3] = {"vorticity_x", "vorticity_y", "vorticity_z"};
  for (std::size_t c = 0; c < vorticity_.size(); ++c)
    fields.push_back({D == 2 ? "vorticity" : names[c], &vorticity_[c]});
  return fields;
}

// A checkpoint is an output: it changes nothing in the run. It records where each particle is stored
// and where the lists were built, for a restart on as many ranks to continue bit for bit.
template <int D> void TimeLoop<D>::write_state(const std::string& why) {
  last_checkpoint_step_ = step_;
  const LogEventScope log_checkpoint(LogEvent::Checkpoint);
  Particles<D>& P = s_.P;
  const std::vector<Vector<D>>& built = s_.nh.x_at_build();
  std::vector<double>& place = P.fields[place_];
  std::vector<Vector<D>>& x_at_build = P.fields[x_at_build_];
  for (std::size_t i = 0; i < P.n_owned; ++i) place[i] = static_cast<double>(P.gid[i]);  // exact below 2^53
  if (built.size() == P.n_owned) std::copy(built.begin(), built.end(), x_at_build.begin());
  std::vector<GlobalIndex> owned(ranks_);
  const GlobalIndex n_owned = static_cast<GlobalIndex>(P.n_owned);
  MPI_Allgather(&n_owned, 1, MPIU_INT, owned.data(), 1, MPIU_INT, PETSC_COMM_WORLD);
  int lists_built = built.size() == P.n_owned;
  MPI_Allreduce(MPI_IN_PLACE, &lists_built, 1, MPI_INT, MPI_MIN, PETSC_COMM_WORLD);
  nlohmann::json run{{"identity", identity_},
                     {"ksp_statistics", stats_.to_json()},
                     {"steady_state_window", steady_.to_json()},
                     {"history", history_},
                     {"case_state", case_.accumulated_state()}};
  if (counts_removed_fluid()) run["removed_fluid"] = {{"particles", removed_.count}, {"mass", removed_.mass}};
  if (s_.disc.open.any()) run["open_boundaries"] = s_.disc.open.state();
  if (s_.disc.bodies.any_free())
    run["free_bodies"] = {{"state", s_.disc.bodies.state()}, {"contact_step", contact_step_}};
  if (wall_groups_) run["moment_about"] = wall_groups_->about();
  if (lists_built) run["order"] = {{"ranks", ranks_}, {"owned", owned}};
  run["history"].push_back(this_segment(why));
  write_checkpoint(checkpoint_path_, s_.P, {t_, step_, solver_.checkpoint_scalars(), run},
                   static_cast<int>(opt_.checkpoints_kept));
}

// A run ended before -t_end by -max_steps or at steady state did what it was asked, and may be continued
// (both options may change on restart): its checkpoint is written, unless -checkpoint_interval 0 asks
// for none, and summary.json says why it stopped where it did.
template <int D> void TimeLoop<D>::stop_early() {
  const bool steps = opt_.max_steps >= 0 && step_ >= opt_.max_steps;
  std::ostringstream why;
  if (steps) why << "-max_steps " << opt_.max_steps << " reached";
  else why << "steady state reached (-steady_tol " << opt_.steady_tol << ")";
  why << " at t = " << t_ << ", before -t_end " << opt_.t_end;
  const bool checkpoint = opt_.checkpoint_interval != 0;
  if (checkpoint && last_checkpoint_step_ != step_) write_state(steps ? "stopped by -max_steps" : "steady state");
  summary_["stopped_early"] = {
      {"reason", steps ? "max_steps" : "steady_state"}, {"detail", why.str()}, {"checkpoint", checkpoint}};
  PetscPrintf(
      PETSC_COMM_WORLD, "stopped early: %s; %s\n", why.str().c_str(),
      checkpoint ? ("continue with -restart " + checkpoint_path_).c_str() : "no checkpoint (-checkpoint_interval 0)");
}

// This run's entry in the history of runs that led to its state.
template <int D> nlohmann::json TimeLoop<D>::this_segment(const std::string& status) const {
  nlohmann::json j{{"status", status},
                   {"steps", {resumed_.step, step_}},
                   {"t", {resumed_.t, t_}},
                   {"wall_time_s", seconds_since(wall_start_)},
                   {"mpi_ranks", ranks_},
                   {"threads_per_rank", opt_.threads},
                   {"version", program_version()},
                   {"command_line", summary_.at("provenance").value("command_line", nlohmann::json())}};
  if (!numerics_changed_.empty()) j["numerics_changed"] = numerics_changed_;
  return j;
}

template <int D> void TimeLoop<D>::finish(const std::string& status, const std::string& failure) {
  const double loop_s = seconds_since(loop_start_);
  nlohmann::json& j = summary_;
  j["status"] = status;
  if (!failure.empty()) j["failure"] = failure;
  j["history"] = history_;
  j["history"].push_back(this_segment(status));
  j["steps"] = step_;
  j["t_final"] = t_;
  j["wall_time_s"] = seconds_since(wall_start_);
  j["time_per_particle_step_s"] = step_ > 0 ? loop_s / (double(step_) * double(s_.P.n_global)) : 0.0;
  j["partition"] = {
      {"curve", "morton"}, {"interval", opt_.partition_interval}, {"count", partitions_}, {"imbalance", s_.imbalance}};
  add_final_state(j, solver_, case_, s_.P, t_, stats_, *initial_);
  if (counts_removed_fluid())
    j["conservation"]["removed_fluid"] = {{"particles", removed_.count}, {"mass", removed_.mass}};
  if (s_.disc.open.any()) {
    j["conservation"]["open_boundaries"] = s_.disc.open.state();
    j["conservation"]["open_boundaries"].erase("next_id");
    j["n_particles_final"] = s_.P.n_global;
  }
  if (s_.disc.bodies.any_free()) j["free_bodies"] = free_body_states(case_.body_names(), s_.disc.bodies);
  write_json_file(run_.output_dir + "/summary.json", j);
}

// A failed run writes its summary and the state that failed, and keeps its earlier frames and checkpoint.
template <int D> void TimeLoop<D>::fail(const Error& e) {
  std::ostringstream msg;
  msg << "step " << failing_step_ << " (t = " << t_ << "): " << e.what();
  // The first failure is the one to report: later ones (a full disk fails every write) are noted.
  std::string also;
  try {
    finish("failed", msg.str());
    case_.write_outputs(s_.P, t_, run_.output_dir);
    // No derived fields: the state may hold NaN. The .pvd lists it last, for inspection.
    write_frame(false);
  } catch (const Error& later) {
    also = later.what() == std::string(e.what())
               ? "; the failed state could not be written either"
               : "; writing the failed run's outputs failed too: " + std::string(later.what());
  }
  // Name only what exists: with -checkpoint_interval 0, or a failure before the first, no checkpoint.
  const bool checkpoint = std::filesystem::exists(checkpoint_path_);
  throw Error(msg.str() + also + " [earlier frames" + (checkpoint ? " and the last checkpoint" : "") + " are kept in " +
              run_.output_dir + (checkpoint ? "" : "; no checkpoint was written") + "]");
}

template <int D> void TimeLoop<D>::stop_interrupted() {
  const std::string signal = signal_name(interrupted_);
  summary_["signal"] = signal;
  summary_["stopped_early"] = {{"reason", "signal"}, {"detail", signal}, {"checkpoint", true}};
  if (opt_.steady_tol > 0) summary_["steady_state_reached"] = steady_.reached();
  case_.write_outputs(s_.P, t_, run_.output_dir);
  finish("interrupted", "");
  std::ostringstream msg;
  msg << "interrupted by " << signal << " after step " << step_ << " (t = " << t_
      << "); frame, checkpoint and summary.json written; resume with -restart " << checkpoint_path_;
  throw Interrupted{interrupted_, msg.str()};
}

}  // namespace

template <int D> void run_time_loop(const RunParts<D>& run) { TimeLoop<D>(run).run(); }

template void run_time_loop<1>(const RunParts<1>&);
template void run_time_loop<2>(const RunParts<2>&);
template void run_time_loop<3>(const RunParts<3>&);

}  // namespace sph
