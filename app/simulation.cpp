#include "app/simulation.hpp"

#include <petscsys.h>

#include <algorithm>
#include <chrono>
#include <deque>
#include <limits>
#include <cmath>
#include <memory>
#include <sstream>

#include "cases/registry.hpp"
#include "solvers/registry.hpp"
#include "src/core/options.hpp"
#include "src/io/checkpoint.hpp"
#include "src/io/csv_writer.hpp"
#include "src/io/json_file.hpp"
#include "src/io/output_dir.hpp"
#include "src/io/particle_writer.hpp"
#include "src/neighbours/partition.hpp"
#include "src/run/diagnostics.hpp"
#include "src/run/interrupt.hpp"
#include "src/run/log_events.hpp"
#include "src/run/progress.hpp"
#include "src/run/provenance.hpp"
#include "src/run/run_identity.hpp"
#include "src/run/threads.hpp"
#include "src/sph/vorticity.hpp"

namespace sph {

// Every case and solver, with its options and whether this run chose it (see check_unused_options).
std::vector<OptionOwner> option_owners(const RunOptions& chosen);

namespace {

// Relative tolerance for comparing times: t is a sum of steps, so t_end, output and checkpoint times
// are reached up to round-off.
constexpr double kTimeTolerance = 1e-12;
// A run has blown up when the kinetic energy exceeds this many times 1/2 M U^2 (README, Outputs).
constexpr double kBlowUpKineticEnergy = 1e3;

// Linear-solver iteration statistics over a run.
struct StepStats {
  long solves = 0, total_iterations = 0;
  int max_iterations = 0;
  void add(const StepReport& r) {
    if (r.linear_iterations < 0) return;
    ++solves, total_iterations += r.linear_iterations;
    max_iterations = std::max(max_iterations, r.linear_iterations);
  }
  double mean_iterations() const { return solves ? double(total_iterations) / solves : 0.0; }
  // Carried by checkpoints, so that a restarted run's figures cover all its steps.
  nlohmann::json to_json() const { return {solves, total_iterations, max_iterations}; }
  void from_json(const nlohmann::json& j) {
    if (j.is_array() && j.size() == 3) solves = j[0], total_iterations = j[1], max_iterations = j[2];
  }
};

// Steady state: the relative kinetic-energy change rate over the last time unit below a tolerance.
class SteadyState {
 public:
  explicit SteadyState(double tol) : tol_(tol) {}
  void add(double t, double ke) {
    if (tol_ <= 0) return;
    history_.emplace_back(t, ke);
    while (history_.size() > 2 && history_[1].first <= t - window_) history_.pop_front();
    const auto& [t0, ke0] = history_.front();
    if (t - t0 >= window_ * (1 - 1e-9) && ke > 0) reached_ = std::abs(ke - ke0) / (ke * (t - t0)) < tol_;
  }
  bool reached() const { return reached_; }
  // The window's history travels with checkpoints: a restart stops where the whole run would.
  nlohmann::json to_json() const { return history_; }
  void from_json(const nlohmann::json& j) {
    if (!j.is_array()) return;
    for (const auto& e : j) history_.emplace_back(e[0].get<double>(), e[1].get<double>());
  }

 private:
  double tol_, window_ = 1.0;
  bool reached_ = false;
  std::deque<std::pair<double, double>> history_;
};

struct DriverOptions {
  PetscReal t_end = 1.0;
  PetscReal dt = 0.0;               // 0: from the solver's stability limits
  PetscInt max_steps = -1;          // -1: no limit
  PetscReal output_interval = -1;   // -1: t_end / 20
  PetscInt kernel = static_cast<PetscInt>(KernelType::WendlandC2);
  PetscReal h_over_dx = -1;         // -1: support radius = 3 dx
  PetscReal skin = 0.2;             // Verlet skin as a fraction of the support radius
  PetscReal steady_tol = -1;        // -1: the case's default
  PetscReal checkpoint_interval = -1;  // -1: with every VTK frame, 0: never
  PetscInt partition_interval = 50;    // steps between re-partitions along the space-filling curve
  PetscInt threads = 0;                // OpenMP threads per rank (0: see configure_threads)
  char restart[PETSC_MAX_PATH_LEN] = "";
  PetscBool progress = PETSC_TRUE;
  PetscBool overwrite = PETSC_FALSE;   // replace a run already in output_dir
  PetscBool dt_force = PETSC_FALSE;    // run a -dt above the stability limit anyway
  char output_dir[PETSC_MAX_PATH_LEN] = "";
  char output_fields[128] = "";        // extra point arrays in the frames: "vorticity"
};

PetscErrorCode read_driver_options(DriverOptions* o) {
  PetscFunctionBeginUser;
  std::vector<const char*> kernels;
  for (const auto& k : kernel_names()) kernels.push_back(k.c_str());
  PetscOptionsBegin(PETSC_COMM_WORLD, nullptr, "Run control, kernel and output", "sph");
  PetscCall(PetscOptionsReal("-t_end", "End time", "", o->t_end, &o->t_end, nullptr));
  PetscCall(PetscOptionsReal("-dt", "Fixed time step (0: from the solver's stability limits)", "", o->dt, &o->dt, nullptr));
  PetscCall(PetscOptionsBool("-dt_force", "Run a -dt above the stability limit instead of refusing it (recorded in summary.json)",
                             "", o->dt_force, &o->dt_force, nullptr));
  PetscCall(PetscOptionsInt("-max_steps", "Stop after this many steps (-1: no limit)", "", o->max_steps, &o->max_steps, nullptr));
  PetscCall(PetscOptionsReal("-output_interval", "Time between VTK frames (-1: t_end/20, 0: first and last only)", "",
                             o->output_interval, &o->output_interval, nullptr));
  PetscCall(PetscOptionsString("-output_dir", "Output directory (default out/<case>-<solver>-<nx>)", "", o->output_dir,
                               o->output_dir, sizeof(o->output_dir), nullptr));
  PetscCall(PetscOptionsString("-output_fields",
                               "Extra point arrays in the VTK frames: vorticity (the solver's own fields, e.g. ISPH's "
                               "free_surface, are always written)",
                               "", o->output_fields, o->output_fields, sizeof(o->output_fields), nullptr));
  PetscCall(PetscOptionsBool("-overwrite", "Replace the run already in -output_dir (its frames, tables, summary, checkpoint)",
                             "", o->overwrite, &o->overwrite, nullptr));
  PetscCall(PetscOptionsEList("-kernel", "Smoothing kernel", "", kernels.data(), static_cast<PetscInt>(kernels.size()),
                              kernels[o->kernel], &o->kernel, nullptr));
  PetscCall(PetscOptionsReal("-h_over_dx", "Smoothing length over particle spacing (-1: support radius 3 dx)", "",
                             o->h_over_dx, &o->h_over_dx, nullptr));
  PetscCall(PetscOptionsReal("-neighbour_skin", "Verlet-list skin as a fraction of the kernel support", "", o->skin,
                             &o->skin, nullptr));
  PetscCall(PetscOptionsReal("-steady_tol",
                             "Stop when |dKE/dt| / KE over the last time unit falls below this (0: run to t_end; "
                             "-1: the case's default)",
                             "", o->steady_tol, &o->steady_tol, nullptr));
  PetscCall(PetscOptionsReal("-checkpoint_interval",
                             "Time between checkpoints (<output_dir>/checkpoint.bin; -1: with every frame, 0: never)", "",
                             o->checkpoint_interval, &o->checkpoint_interval, nullptr));
  PetscCall(PetscOptionsInt("-partition_interval",
                            "Steps between re-orderings of the particles along a space-filling curve, which also "
                            "re-balances them over MPI ranks (0: only at start-up and at checkpoints)",
                            "", o->partition_interval, &o->partition_interval, nullptr));
  PetscCall(PetscOptionsInt("-threads",
                            "OpenMP threads per MPI rank for the pair loops, neighbour search and PPE assembly (0: "
                            "OMP_NUM_THREADS if set, else this rank's cores shared with the other ranks on the node)",
                            "", o->threads, &o->threads, nullptr));
  PetscCall(PetscOptionsString("-restart", "Resume from this checkpoint (same case, solver and options)", "", o->restart,
                               o->restart, sizeof(o->restart), nullptr));
  PetscCall(PetscOptionsBool("-progress", "Print a progress line on stderr about once a second", "", o->progress,
                             &o->progress, nullptr));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

template <int D> struct Run {
  std::unique_ptr<Case<D>> scene_case;
  std::unique_ptr<Solver<D>> solver;
  DriverOptions opt;
  RunOptions names;
  std::string output_dir;
  bool vorticity_output = false;

  void configure() {
    scene_case->set_from_options();
    solver->set_from_options();
    opt.t_end = scene_case->default_t_end();
    SPH_PETSC(read_driver_options(&opt));
    require(opt.t_end > 0, "-t_end", "positive", opt.t_end);
    require(opt.dt >= 0, "-dt", "non-negative", opt.dt);
    require(opt.max_steps >= -1, "-max_steps", "-1 (no limit) or non-negative", opt.max_steps);
    require(opt.output_interval == -1 || opt.output_interval >= 0, "-output_interval",
            "-1 (t_end/20), 0 (first and last frame) or positive", opt.output_interval);
    require(opt.checkpoint_interval == -1 || opt.checkpoint_interval >= 0, "-checkpoint_interval",
            "-1 (with every frame), 0 (never) or positive", opt.checkpoint_interval);
    require(opt.steady_tol == -1 || opt.steady_tol >= 0, "-steady_tol", "-1 (the case's default), 0 (off) or positive",
            opt.steady_tol);
    require(opt.h_over_dx == -1 || opt.h_over_dx > 0, "-h_over_dx", "positive", opt.h_over_dx);
    require(opt.skin >= 0 && opt.skin <= 1, "-neighbour_skin", "in [0, 1]", opt.skin);
    require(opt.partition_interval >= 0, "-partition_interval", "non-negative", opt.partition_interval);
    require(opt.threads >= 0, "-threads", "non-negative", opt.threads);
    opt.threads = configure_threads(static_cast<int>(opt.threads));
    std::stringstream fields(opt.output_fields);
    for (std::string f; std::getline(fields, f, ',');) {
      if (f != "vorticity") throw Error("-output_fields takes vorticity (got '" + f + "')");
      if (D == 1) throw Error("-output_fields vorticity needs a 2D or 3D scene");
      vorticity_output = true;
    }
    if (opt.output_interval < 0) opt.output_interval = opt.t_end / 20;
    if (opt.steady_tol < 0) opt.steady_tol = scene_case->steady_tolerance();
    output_dir = opt.output_dir[0] ? std::string(opt.output_dir)
                                   : "out/" + scene_case->output_name() + "-" + names.solver_name + "-" +
                                         std::to_string(scene_case->resolution());
    check_unused_options(option_owners(names));
  }

  void execute();
};

template <int D> void Run<D>::execute() {
  const auto wall_start = std::chrono::steady_clock::now();
  // A restart must continue the run that wrote the checkpoint: refused before any work if the
  // checkpoint is damaged or was written with other options.
  const bool restarting = opt.restart[0] != '\0';
  const nlohmann::json identity = run_identity(names.case_name, names.solver_name, D, scene_case->parameters());
  nlohmann::json resumed_run = nlohmann::json::object();
  if (restarting) {
    resumed_run = read_checkpoint_header(opt.restart).value("run", nlohmann::json::object());
    check_same_run(resumed_run.value("identity", nlohmann::json()), identity, opt.restart);
  }
  Particles<D> P;
  Domain<D> domain;
  scene_case->create(P, domain);
  assign_global_indices(P);
  double imbalance = partition_along_curve(P, domain);
  long partitions = 1;

  const KernelType ktype = static_cast<KernelType>(opt.kernel);
  const double dx = scene_case->spacing();
  const double h_over_dx = opt.h_over_dx > 0 ? opt.h_over_dx : 3.0 / Kernel<D>::support_factor(ktype);
  const Kernel<D> kernel(ktype, h_over_dx * dx);
  if (scene_case->wall_thickness() > 0 && scene_case->wall_thickness() < kernel.support_radius() * (1 - 1e-12))
    throw Error(scene_case->thin_walls(scene_case->wall_thickness() / dx, kernel.support_radius() / dx));
  Neighbourhood<D> nh(domain, kernel.support_radius(), opt.skin * kernel.support_radius());
  Scene<D> scene{P, nh, kernel, scene_case->physics(), dx};
  solver->setup(scene);

  // Re-orders and re-balances the particles (with the solver's per-particle state) along the curve
  // and rebuilds the neighbourhood: the canonical state, which depends only on the particles.
  auto repartition = [&] {
    imbalance = partition_along_curve(P, domain, [&] { return solver->checkpoint_fields(); });
    ++partitions;
    nh.update(P, true);
  };

  // A restart overwrites the freshly set-up state with the checkpoint's, then brings it into the
  // canonical state, as the writing run did before writing it.
  CheckpointState<D> resumed;
  if (restarting) {
    resumed = read_checkpoint(opt.restart, P, solver->checkpoint_fields());
    solver->restore_scalars(resumed.scalars);
    repartition();
  }
  check_initial_state(P, resumed.t);
  const std::string checkpoint_path = output_dir + "/checkpoint.bin";
  auto dt_above_limit = [&](double stable, double t_now) {
    std::ostringstream msg;
    msg << "-dt " << opt.dt << " exceeds the scheme's stability limit " << stable << " at t = " << t_now;
    return msg.str();
  };
  if (opt.dt > 0 && !opt.dt_force && opt.dt > solver->stable_dt())
    throw Error(dt_above_limit(solver->stable_dt(), resumed.t) +
                "; lower -dt (-dt 0 follows the limit) or pass -dt_force 1 to run it anyway");
  // Only now, with the input accepted, may an earlier run in output_dir go (-overwrite).
  const bool in_place = restarting && is_in_directory(opt.restart, output_dir);
  prepare_output_dir(output_dir, opt.overwrite, in_place);

  ParticleWriter<D> writer(output_dir);
  if (restarting) writer.resume(resumed.t);
  // The solver's own fields and the optional ones, for every frame.
  std::vector<std::vector<double>> vorticity;
  auto frame_fields = [&](bool derived = true) {
    std::vector<ScalarField> fields = solver->output_fields();
    if (!vorticity_output || !derived) return fields;
    nh.update(P);  // ghost velocities as the step left the owned ones
    vorticity = fluid_vorticity(P, nh.list(), kernel);
    const char* names[3] = {"vorticity_x", "vorticity_y", "vorticity_z"};
    for (std::size_t c = 0; c < vorticity.size(); ++c) fields.push_back({D == 2 ? "vorticity" : names[c], &vorticity[c]});
    return fields;
  };
  if (in_place) remove_frames_from(output_dir, "particles", writer.frames_written());
  const std::vector<std::string> error_names = [&] {
    std::vector<std::string> v;
    for (const auto& e : scene_case->errors(P, 0.0)) v.push_back(e.first);
    return v;
  }();
  std::vector<std::string> columns = {"step", "t", "dt", "kinetic_energy"};
  for (int a = 0; a < D; ++a) columns.push_back(std::string("momentum_") + "xyz"[a]);
  columns.insert(columns.end(), {"ksp_iterations", "ksp_reason"});
  columns.insert(columns.end(), error_names.begin(), error_names.end());
  CsvWriter series = restarting ? CsvWriter(output_dir + "/timeseries.csv", columns, 1, resumed.t)
                                : CsvWriter(output_dir + "/timeseries.csv", columns);

  nlohmann::json summary;
  summary["case"] = names.case_name;
  summary["solver"] = names.solver_name;
  summary["dim"] = D;
  summary["n_particles"] = P.n_global;
  summary["dx"] = dx;
  summary["kernel"] = {{"type", kernel.name()}, {"h", kernel.h()}, {"h_over_dx", h_over_dx}};
  summary["t_end"] = opt.t_end;
  summary["parameters"] = scene_case->parameters();
  summary["physics"] = scene.physics.describe();
  PetscMPIInt ranks;
  MPI_Comm_size(PETSC_COMM_WORLD, &ranks);
  summary["mpi_ranks"] = ranks;
  summary["threads_per_rank"] = opt.threads;
  summary["provenance"] = provenance(static_cast<int>(opt.threads));

  const Totals<D> initial = totals(P);
  SteadyState steady(opt.steady_tol);
  double t = resumed.t;
  long step = resumed.step;
  StepStats stats;
  stats.from_json(resumed_run.value("ksp_statistics", nlohmann::json()));
  steady.from_json(resumed_run.value("steady_state_window", nlohmann::json()));
  // The runs that led to the checkpoint this one resumes, then this one.
  nlohmann::json history = resumed_run.value("history", nlohmann::json::array());
  auto this_segment = [&](const std::string& status) {
    return nlohmann::json{{"status", status}, {"steps", {resumed.step, step}}, {"t", {resumed.t, t}},
                          {"wall_time_s", std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count()},
                          {"mpi_ranks", ranks}, {"threads_per_rank", opt.threads}, {"version", program_version()},
                          {"command_line", summary["provenance"]["command_line"]}};
  };
  long last_checkpoint_step = -1, failing_step = step + 1;
  int interrupted = 0;  // the signal that stopped the run
  auto write_state = [&](double t_now, long step_now, const std::string& why = "checkpointed") {
    last_checkpoint_step = step_now;
    repartition();
    const LogEventScope log_checkpoint(LogEvent::Checkpoint);
    nlohmann::json run{{"identity", identity}, {"ksp_statistics", stats.to_json()},
                       {"steady_state_window", steady.to_json()}, {"history", history}};
    run["history"].push_back(this_segment(why));
    write_checkpoint(checkpoint_path, P, solver->checkpoint_fields(),
                     {t_now, step_now, solver->checkpoint_scalars(), run});
  };
  Progress progress(opt.progress, opt.t_end);
  const double frame_interval = opt.output_interval > 0 ? opt.output_interval : opt.t_end;
  double next_output = frame_interval * (std::floor(t / frame_interval * (1.0 + kTimeTolerance)) + 1);
  const double checkpoint_interval = opt.checkpoint_interval < 0 ? frame_interval : opt.checkpoint_interval;
  double next_checkpoint = checkpoint_interval > 0 ? checkpoint_interval * (std::floor(t / checkpoint_interval * (1.0 + kTimeTolerance)) + 1)
                                                   : std::numeric_limits<double>::infinity();
  if (!restarting) writer.write(P, t, frame_fields());
  double last_frame_t = t;
  const double ke_bound = kBlowUpKineticEnergy * 0.5 * fluid_mass(P) * scene.physics.U * scene.physics.U;
  // A -dt above the stability limit is refused at the start unless -dt_force; a forced one, or the
  // limit falling below -dt later, is a warning, printed once and kept in summary.json.
  bool warned_dt = false;
  auto warn_dt = [&](double stable) {
    if (warned_dt) return;
    const std::string w = dt_above_limit(stable, t) + "; the run may blow up";
    PetscFPrintf(PETSC_COMM_WORLD, stderr, "sph: warning: %s\n", w.c_str());
    summary["warnings"].push_back(w);
    warned_dt = true;
  };
  NeighbourCountCheck<D> check_neighbours(scene.physics.free_surface);
  check_neighbours(P, nh.list(), nh.support_radius());  // the reference counts
  const auto loop_start = std::chrono::steady_clock::now();
  auto finish = [&](const std::string& status, const std::string& failure) {
    const double loop_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - loop_start).count();
    summary["status"] = status;
    if (!failure.empty()) summary["failure"] = failure;
    summary["history"] = history;
    summary["history"].push_back(this_segment(status));
    summary["steps"] = step;
    summary["t_final"] = t;
    summary["wall_time_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    summary["time_per_particle_step_s"] = step > 0 ? loop_s / (double(step) * double(P.n_global)) : 0.0;
    nlohmann::json solver_info = solver->describe();
    summary["models"] = solver_info["models"];
    if (solver_info.contains("ksp")) {
      summary["ksp"] = solver_info["ksp"];
      summary["ksp"]["iterations_mean"] = stats.mean_iterations();
      summary["ksp"]["iterations_max"] = stats.max_iterations;
    }
    // Total momentum change relative to the initial sum of |m v|: round-off for pairwise-symmetric
    // schemes without shifting (shifting's Taylor correction and corrected gradients do not conserve it).
    const Totals<D> now = totals(P);
    summary["partition"] = {{"curve", "morton"}, {"interval", opt.partition_interval}, {"count", partitions},
                            {"imbalance", imbalance}};
    // Relative to the larger of the initial and final sums of |m v|: a scene that starts at rest
    // (the cavity) has no initial scale to measure against.
    summary["conservation"] = {{"momentum_drift", (now.momentum - initial.momentum).norm() /
                                                      std::max({initial.momentum_scale, now.momentum_scale, 1e-300})}};
    for (auto it = solver_info.begin(); it != solver_info.end(); ++it) {
      if (it.key() == "models" || it.key() == "ksp") continue;
      if (it.key() == "conservation") summary["conservation"].update(it.value());
      else summary["solver_parameters"][it.key()] = it.value();
    }
    summary["errors"] = nlohmann::json::object();
    for (const auto& [name, value] : scene_case->errors(P, t)) {
      summary["errors"][name] = value;  // NaN becomes null: a metric that could not be measured
      if (std::isfinite(value)) continue;
      const std::string why = scene_case->unmeasured_reason(name);
      summary["errors_unmeasured"][name] = why.empty() ? "not a finite number at the end of the run" : why;
    }
    write_json_file(output_dir + "/summary.json", summary);
  };

  try {
    const TimeLoopLogStage log_stage;
    while (t < opt.t_end * (1.0 - kTimeTolerance) && (opt.max_steps < 0 || step < opt.max_steps) && !steady.reached()) {
      const double stable = solver->stable_dt();
      double dt = opt.dt > 0 ? opt.dt : stable;
      if (opt.dt > stable) warn_dt(stable);
      // Equal steps that land on t_end: a last sliver of a step would be a different discretisation
      // (ISPH's pressure scales with 1/dt).
      const double remaining = opt.t_end - t;
      dt = remaining / std::ceil(remaining / dt * (1.0 - kTimeTolerance));
      LogEventScope log_step(LogEvent::Step);
      failing_step = step + 1;
      const StepReport report = solver->step(dt);
      log_step.end();
      t += dt;
      ++step;
      failing_step = step;  // what fails from here on (checks, output) belongs to the step just made
      stats.add(report);
      if (step == resumed.step + 1) check_late_options(option_owners(names));
      LogEventScope log_diagnostics(LogEvent::Diagnostics);
      check_health(P, domain, ke_bound);
      check_neighbours(P, nh.list(), nh.support_radius());
      if (opt.partition_interval > 0 && step % opt.partition_interval == 0) repartition();

      const Totals<D> tot = totals(P);
      steady.add(t, tot.kinetic_energy);
      std::vector<double> row = {double(step), t, dt, tot.kinetic_energy};
      for (int a = 0; a < D; ++a) row.push_back(tot.momentum[a]);
      row.push_back(report.linear_iterations);
      row.push_back(report.linear_reason);
      for (const auto& e : scene_case->errors(P, t)) row.push_back(e.second);
      series.row(row);
      log_diagnostics.end();
      progress.update(step, t, dt, report.linear_iterations);
      if (t >= next_output * (1.0 - kTimeTolerance) || t >= opt.t_end * (1.0 - kTimeTolerance)) {
        const LogEventScope log_output(LogEvent::Output);
        writer.write(P, t, frame_fields());
        last_frame_t = t;
        while (next_output <= t * (1.0 + kTimeTolerance)) next_output += frame_interval;
      }
      if (t >= next_checkpoint * (1.0 - kTimeTolerance)) {
        write_state(t, step);
        while (next_checkpoint <= t * (1.0 + kTimeTolerance)) next_checkpoint += checkpoint_interval;
      }
      if ((interrupted = interrupt_requested())) break;  // all ranks see the same answer
    }
    if (interrupted) {
      // Everything needed to look at the state reached and to resume it.
      if (last_frame_t < t) writer.write(P, t, frame_fields()), last_frame_t = t;
      if (last_checkpoint_step != step) write_state(t, step, "interrupted (" + signal_name(interrupted) + ")");
    }
  } catch (const OptionError&) {
    throw;  // a mistake in the command line, not a failed run
  } catch (const Error& e) {
    std::ostringstream msg;
    msg << "step " << failing_step << " (t = " << t << "): " << e.what();
    // The first failure is the one to report: later ones (a full disk fails every write) are noted.
    std::string also;
    try {
      finish("failed", msg.str());
      scene_case->write_outputs(P, t, output_dir);
      writer.write(P, t, frame_fields(false));  // the state that failed (no derived fields: it may hold NaN), for inspection (the .pvd lists it last)
    } catch (const Error& later) {
      also = "; writing the failed run's outputs failed too: " + std::string(later.what());
    }
    throw Error(msg.str() + also + " [earlier frames and the last checkpoint are kept in " + output_dir + "]");
  }
  progress.done(step, t);
  if (interrupted) {
    summary["signal"] = signal_name(interrupted);
    if (opt.steady_tol > 0) summary["steady_state_reached"] = steady.reached();
    scene_case->write_outputs(P, t, output_dir);
    finish("interrupted", "");
    std::ostringstream msg;
    msg << "interrupted by " << signal_name(interrupted) << " after step " << step << " (t = " << t
        << "); frame, checkpoint and summary.json written; resume with -restart " << checkpoint_path;
    throw Interrupted{interrupted, msg.str()};
  }
  const LogEventScope log_output(LogEvent::Output);
  if (opt.steady_tol > 0) summary["steady_state_reached"] = steady.reached();
  scene_case->write_outputs(P, t, output_dir);
  if (last_frame_t < t) writer.write(P, t, frame_fields());  // e.g. stopped at steady state between frames
  finish("completed", "");
  finish_options_check();
}

template <int D> void run_in_dim(const RunOptions& names) {
  Run<D> run;
  run.names = names;
  run.scene_case = create_case<D>(names.case_name);
  run.solver = create_solver<D>(names.solver_name);
  run.configure();
  run.execute();
}

}  // namespace

std::vector<OptionOwner> option_owners(const RunOptions& chosen) {
  std::vector<OptionOwner> owners;
  for (const auto& entry : case_registry()) {
    OptionOwner o{"-case " + entry.name, {}, {}, entry.name == chosen.case_name};
    if (entry.make2) o.read = [&entry] { entry.make2()->set_from_options(); };
    else if (entry.make1) o.read = [&entry] { entry.make1()->set_from_options(); };
    else if (entry.make3) o.read = [&entry] { entry.make3()->set_from_options(); };
    owners.push_back(o);
  }
  for (const auto& name : solver_names()) {
    auto reads_late = [name](const std::string& option) { return create_solver<2>(name)->reads_late(option); };
    owners.push_back({"-solver " + name, [name] { create_solver<2>(name)->set_from_options(); }, reads_late,
                      name == chosen.solver_name});
  }
  owners.push_back({"", [] {  // run control: read by every run
                      DriverOptions opt;
                      SPH_PETSC(read_driver_options(&opt));
                    }, {}, true});
  return owners;
}

void print_all_options(int) {
  // Reading an options block with -help set prints it; the values are not used, so a value check
  // failing for one component (an -nx another case would refuse) must not hide the others.
  for (const OptionOwner& o : option_owners(RunOptions{})) {
    try {
      o.read();
    } catch (const Error&) {
    }
  }
}

void run_simulation(const RunOptions& opts, int dim) {
  switch (dim) {
    case 1: run_in_dim<1>(opts); break;
    case 2: run_in_dim<2>(opts); break;
    case 3: run_in_dim<3>(opts); break;
    default: throw Error("-dim must be 1, 2 or 3 (got " + std::to_string(dim) + ")");
  }
}

}  // namespace sph
