// The time loop's class, shared by its three files: time_loop.cpp (the steps), time_loop_outputs.cpp
// (frames, timeseries.csv, summary.json) and time_loop_checkpoints.cpp (checkpoints, restarts, the
// ways a run stops). Internal to src/run/: everything else calls run_time_loop (time_loop.hpp).
#pragma once

#include <petscsys.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <sstream>

#include "src/boundary/body_contact.hpp"
#include "src/boundary/wall_model.hpp"
#include "src/core/log_events.hpp"
#include "src/core/options.hpp"
#include "src/io/checkpoint.hpp"
#include "src/io/csv_writer.hpp"
#include "src/io/json_file.hpp"
#include "src/io/output_dir.hpp"
#include "src/io/particle_writer.hpp"
#include "src/neighbours/partition.hpp"
#include "src/run/body_checks.hpp"
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
#include "src/run/time_loop.hpp"
#include "src/run/wall_groups.hpp"
#include "src/sph/vorticity.hpp"

namespace sph::time_loop_detail {

// A run has blown up when the kinetic energy exceeds this many times 1/2 M U^2 (docs/user-guide.md).
constexpr double kBlowUpKineticEnergy = 1e3;

using Clock = std::chrono::steady_clock;
inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
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
  void check_bodies();
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
  std::vector<Probe<D>> probes_;              // the case's pressure probes (empty: none, and no reduction per step)
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
  std::vector<int> warned_in_walls_;                    // by body: said that its motion drives it into a fixed wall
  double contact_step_ = 0.0;                           // > 0: a free body is near a contact, the step held to this
  double faces_t_ = -1.0;                               // when wall_groups_ last computed the bodies' face pressures
  bool surface_column_ = false, walls_column_ = false;  // timeseries.csv's free_surface_share, fluid_in_walls
  RemovedFluid removed_;  // -box_exit auto or remove: the fluid taken out so far (timeseries.csv's removed_fluid)
  int removal_events_ = 0;
  double last_frame_t_ = 0.0, ke_bound_ = 0.0;
  std::optional<Progress> progress_;
  std::optional<Cadence> frames_, checkpoints_;
  NeighbourCountCheck<D> check_neighbours_;
  Clock::time_point loop_start_;
};

}  // namespace sph::time_loop_detail
