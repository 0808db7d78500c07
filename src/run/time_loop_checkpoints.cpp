#include "src/run/time_loop_detail.hpp"

namespace sph {

namespace time_loop_detail {

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

// Each member is compiled once, in the file that defines it, for 1, 2 and 3 dimensions.
#define SPH_INSTANTIATE_TIME_LOOP_CHECKPOINTS(D)                   \
  template nlohmann::json TimeLoop<D>::checked_restart() const;    \
  template nlohmann::json TimeLoop<D>::resumed_run_header() const; \
  template void TimeLoop<D>::resume();                             \
  template void TimeLoop<D>::restore_order_and_lists();            \
  template void TimeLoop<D>::write_state(const std::string& why);  \
  template void TimeLoop<D>::stop_early();                         \
  template void TimeLoop<D>::fail(const Error& e);                 \
  template void TimeLoop<D>::stop_interrupted();
SPH_INSTANTIATE_TIME_LOOP_CHECKPOINTS(1)
SPH_INSTANTIATE_TIME_LOOP_CHECKPOINTS(2)
SPH_INSTANTIATE_TIME_LOOP_CHECKPOINTS(3)
#undef SPH_INSTANTIATE_TIME_LOOP_CHECKPOINTS

}  // namespace time_loop_detail

}  // namespace sph
