#include "src/run/time_loop.hpp"

#include <petscsys.h>

#include <chrono>
#include <cmath>
#include <sstream>

#include "src/core/log_events.hpp"
#include "src/core/options.hpp"
#include "src/io/checkpoint.hpp"
#include "src/io/csv_writer.hpp"
#include "src/io/json_file.hpp"
#include "src/io/output_dir.hpp"
#include "src/io/particle_writer.hpp"
#include "src/neighbours/partition.hpp"
#include "src/run/diagnostics.hpp"
#include "src/run/interrupt.hpp"
#include "src/run/progress.hpp"
#include "src/run/provenance.hpp"
#include "src/run/run_identity.hpp"
#include "src/run/run_statistics.hpp"
#include "src/run/run_summary.hpp"
#include "src/run/schedule.hpp"
#include "src/sph/vorticity.hpp"

namespace sph {

namespace {
// A run has blown up when the kinetic energy exceeds this many times 1/2 M U^2 (README, Outputs).
constexpr double kBlowUpKineticEnergy = 1e3;
}  // namespace

template <int D> void run_time_loop(const RunParts<D>& run) {
  const RunControl& opt = run.control;
  Case<D>& scene_case = run.scene_case;
  Solver<D>& solver = run.solver;
  const std::string& output_dir = run.output_dir;
  const auto wall_start = std::chrono::steady_clock::now();
  // A restart must continue the run that wrote the checkpoint: refused before any work if the
  // checkpoint is damaged or was written with other options.
  const bool restarting = opt.restarting();
  const nlohmann::json identity = run_identity(run.case_name, run.solver_name, D, scene_case.parameters());
  nlohmann::json resumed_run = nlohmann::json::object();
  if (restarting) {
    resumed_run = read_checkpoint_header(opt.restart).value("run", nlohmann::json::object());
    check_same_run(resumed_run.value("identity", nlohmann::json()), identity, opt.restart);
  }
  Particles<D> P;
  Domain<D> domain;
  scene_case.create(P, domain);
  assign_global_indices(P);
  double imbalance = partition_along_curve(P, domain);
  long partitions = 1;

  const double dx = scene_case.spacing();
  const Kernel<D> kernel = run.kernel.template make<D>(dx);
  if (scene_case.wall_thickness() > 0 && scene_case.wall_thickness() < kernel.support_radius() * (1 - 1e-12))
    throw Error(scene_case.thin_walls(scene_case.wall_thickness() / dx, kernel.support_radius() / dx));
  Neighbourhood<D> nh(domain, kernel.support_radius(), opt.skin * kernel.support_radius());
  Scene<D> scene{P, nh, kernel, scene_case.physics(), dx};
  solver.setup(scene);

  // Re-orders and re-balances the particles (with the solver's per-particle state) along the curve
  // and rebuilds the neighbourhood: the canonical state, which depends only on the particles.
  auto repartition = [&] {
    imbalance = partition_along_curve(P, domain, [&] { return solver.checkpoint_fields(); });
    ++partitions;
    nh.update(P, true);
  };

  // A restart overwrites the freshly set-up state with the checkpoint's, then brings it into the
  // canonical state, as the writing run did before writing it.
  CheckpointState<D> resumed;
  if (restarting) {
    resumed = read_checkpoint(opt.restart, P, solver.checkpoint_fields());
    solver.restore_scalars(resumed.scalars);
    repartition();
  }
  check_initial_state(P, resumed.t);
  const std::string checkpoint_path = output_dir + "/checkpoint.bin";
  auto dt_above_limit = [&](double stable, double t_now) {
    std::ostringstream msg;
    msg << "-dt " << opt.dt << " exceeds the scheme's stability limit " << stable << " at t = " << t_now;
    return msg.str();
  };
  if (opt.dt > 0 && !opt.dt_force && opt.dt > solver.stable_dt())
    throw Error(dt_above_limit(solver.stable_dt(), resumed.t) +
                "; lower -dt (-dt 0 follows the limit) or pass -dt_force 1 to run it anyway");
  // Only now, with the input accepted, may an earlier run in output_dir go (-overwrite).
  const bool in_place = restarting && is_in_directory(opt.restart, output_dir);
  prepare_output_dir(output_dir, opt.overwrite, in_place);

  ParticleWriter<D> writer(output_dir);
  if (restarting) writer.resume(resumed.t);
  // The solver's own fields and the optional ones, for every frame.
  std::vector<std::vector<double>> vorticity;
  auto frame_fields = [&](bool derived = true) {
    std::vector<ScalarField> fields = solver.output_fields();
    if (!opt.vorticity_output || !derived) return fields;
    nh.update(P);  // ghost velocities as the step left the owned ones
    vorticity = fluid_vorticity(P, nh.list(), kernel);
    const char* names[3] = {"vorticity_x", "vorticity_y", "vorticity_z"};
    for (std::size_t c = 0; c < vorticity.size(); ++c) fields.push_back({D == 2 ? "vorticity" : names[c], &vorticity[c]});
    return fields;
  };
  if (in_place) remove_frames_from(output_dir, "particles", writer.frames_written());
  const std::vector<std::string> error_names = [&] {
    std::vector<std::string> v;
    for (const auto& e : scene_case.errors(P, 0.0)) v.push_back(e.first);
    return v;
  }();
  std::vector<std::string> columns = {"step", "t", "dt", "kinetic_energy"};
  for (int a = 0; a < D; ++a) columns.push_back(std::string("momentum_") + "xyz"[a]);
  columns.insert(columns.end(), {"ksp_iterations", "ksp_reason"});
  columns.insert(columns.end(), error_names.begin(), error_names.end());
  CsvWriter series = restarting ? CsvWriter(output_dir + "/timeseries.csv", columns, 1, resumed.t)
                                : CsvWriter(output_dir + "/timeseries.csv", columns);

  nlohmann::json summary;
  summary["case"] = run.case_name;
  summary["solver"] = run.solver_name;
  summary["dim"] = D;
  summary["n_particles"] = P.n_global;
  summary["dx"] = dx;
  summary["kernel"] = {{"type", kernel.name()}, {"h", kernel.h()}, {"h_over_dx", run.kernel.template resolved_h_over_dx<D>()}};
  summary["t_end"] = opt.t_end;
  summary["parameters"] = scene_case.parameters();
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
    write_checkpoint(checkpoint_path, P, solver.checkpoint_fields(),
                     {t_now, step_now, solver.checkpoint_scalars(), run});
  };
  Progress progress(opt.progress, opt.t_end);
  const double frame_interval = opt.output_interval > 0 ? opt.output_interval : opt.t_end;
  Cadence frames(frame_interval, t);
  Cadence checkpoints(opt.checkpoint_interval < 0 ? frame_interval : opt.checkpoint_interval, t);
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
    summary["partition"] = {{"curve", "morton"}, {"interval", opt.partition_interval}, {"count", partitions},
                            {"imbalance", imbalance}};
    add_final_state(summary, solver, scene_case, P, t, stats, initial);
    write_json_file(output_dir + "/summary.json", summary);
  };

  try {
    const TimeLoopLogStage log_stage;
    while (!time_reached(t, opt.t_end) && (opt.max_steps < 0 || step < opt.max_steps) && !steady.reached()) {
      const double stable = solver.stable_dt();
      double dt = opt.dt > 0 ? opt.dt : stable;
      if (opt.dt > stable) warn_dt(stable);
      dt = step_to_end(t, opt.t_end, dt);
      LogEventScope log_step(LogEvent::Step);
      failing_step = step + 1;
      const StepReport report = solver.step(dt);
      log_step.end();
      t += dt;
      ++step;
      failing_step = step;  // what fails from here on (checks, output) belongs to the step just made
      stats.add(report);
      if (step == resumed.step + 1 && run.after_first_step) run.after_first_step();
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
      for (const auto& e : scene_case.errors(P, t)) row.push_back(e.second);
      series.row(row);
      log_diagnostics.end();
      progress.update(step, t, dt, report.linear_iterations);
      if (frames.due(t) || time_reached(t, opt.t_end)) {
        const LogEventScope log_output(LogEvent::Output);
        writer.write(P, t, frame_fields());
        last_frame_t = t;
        frames.advance(t);
      }
      if (checkpoints.due(t)) {
        write_state(t, step);
        checkpoints.advance(t);
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
      scene_case.write_outputs(P, t, output_dir);
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
    scene_case.write_outputs(P, t, output_dir);
    finish("interrupted", "");
    std::ostringstream msg;
    msg << "interrupted by " << signal_name(interrupted) << " after step " << step << " (t = " << t
        << "); frame, checkpoint and summary.json written; resume with -restart " << checkpoint_path;
    throw Interrupted{interrupted, msg.str()};
  }
  const LogEventScope log_output(LogEvent::Output);
  if (opt.steady_tol > 0) summary["steady_state_reached"] = steady.reached();
  scene_case.write_outputs(P, t, output_dir);
  if (last_frame_t < t) writer.write(P, t, frame_fields());  // e.g. stopped at steady state between frames
  finish("completed", "");
}

template void run_time_loop<1>(const RunParts<1>&);
template void run_time_loop<2>(const RunParts<2>&);
template void run_time_loop<3>(const RunParts<3>&);

}  // namespace sph
