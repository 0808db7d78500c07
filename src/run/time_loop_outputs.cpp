#include "src/run/time_loop_detail.hpp"

namespace sph {

namespace time_loop_detail {

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
  probes_ = case_.probes();
  const std::vector<std::string> probe_names = probe_columns(probes_);
  columns.insert(columns.end(), probe_names.begin(), probe_names.end());
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
    // The faces' loads where the step's forces took them (not in the first frame, before any step).
    if (!wall_groups_ || faces_t_ != t_) {
      surface_writers_[b].write(surface, t_);
      continue;
    }
    const std::vector<Vector<D>> shear =
        wall_groups_->face_shear(b, s_.P, s_.nh, s_.kernel, s_.disc.physics, s_.disc.bodies, s_.disc.walls.get());
    std::vector<std::array<double, 3>> shear3(shear.size(), {0.0, 0.0, 0.0});
    for (std::size_t q = 0; q < shear.size(); ++q)
      for (int a = 0; a < D; ++a) shear3[q][a] = shear[q][a];
    surface_writers_[b].write(surface, t_, &wall_groups_->face_pressure(b), &shear3);
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
    j["conservation"]["open_boundaries"].erase("outlet_mean_outward_velocity");
    j["n_particles_final"] = s_.P.n_global;
  }
  if (s_.disc.bodies.any_free()) j["free_bodies"] = free_body_states(case_.body_names(), s_.disc.bodies);
  write_json_file(run_.output_dir + "/summary.json", j);
}

// Each member is compiled once, in the file that defines it, for 1, 2 and 3 dimensions.
#define SPH_INSTANTIATE_TIME_LOOP_OUTPUTS(D)                                          \
  template void TimeLoop<D>::open_outputs();                                          \
  template void TimeLoop<D>::describe_run();                                          \
  template void TimeLoop<D>::write_due_outputs();                                     \
  template void TimeLoop<D>::write_frame(bool derived);                               \
  template std::vector<ScalarField> TimeLoop<D>::frame_fields(bool derived);          \
  template nlohmann::json TimeLoop<D>::this_segment(const std::string& status) const; \
  template void TimeLoop<D>::finish(const std::string& status, const std::string& failure);
SPH_INSTANTIATE_TIME_LOOP_OUTPUTS(1)
SPH_INSTANTIATE_TIME_LOOP_OUTPUTS(2)
SPH_INSTANTIATE_TIME_LOOP_OUTPUTS(3)
#undef SPH_INSTANTIATE_TIME_LOOP_OUTPUTS

}  // namespace time_loop_detail

}  // namespace sph
