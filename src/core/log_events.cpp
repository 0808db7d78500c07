#include "src/core/log_events.hpp"

#include <array>

namespace sph {

namespace {

PetscClassId sph_class() {
  static const PetscClassId id = [] {
    PetscClassId c = 0;
    PetscClassIdRegister("SPH", &c);
    return c;
  }();
  return id;
}

struct Registered {
  std::array<PetscLogEvent, static_cast<int>(LogEvent::Count)> events{};
  PetscLogStage time_loop = 0;

  Registered() {
    static const char* const names[] = {"SPHStep",     "SPHNbrUpdate",   "SPHNbrRebuild", "SPHDensity",   "SPHForces",
                                        "SPHShifting", "SPHDiagnostics", "SPHOutput",     "SPHCheckpoint"};
    static_assert(sizeof(names) / sizeof(names[0]) == static_cast<int>(LogEvent::Count), "one name per event");
    for (int k = 0; k < static_cast<int>(LogEvent::Count); ++k)
      PetscLogEventRegister(names[k], sph_class(), &events[k]);
    PetscLogStageRegister("SPH time loop", &time_loop);
  }
};

const Registered& registered() {
  static const Registered r;
  return r;
}

}  // namespace

PetscLogEvent log_event(LogEvent e) { return registered().events[static_cast<int>(e)]; }

PetscLogStage time_loop_log_stage() { return registered().time_loop; }

PetscLogEvent register_log_event(const char* name) {
  registered();  // the core's events first, so -log_view lists them in one block
  PetscLogEvent e = 0;
  PetscLogEventRegister(name, sph_class(), &e);
  return e;
}

LogEventScope::LogEventScope(PetscLogEvent e) : event_(e) { (void)PetscLogEventBegin(event_, 0, 0, 0, 0); }

void LogEventScope::end() {
  if (!open_) return;
  open_ = false;
  (void)PetscLogEventEnd(event_, 0, 0, 0, 0);
}

TimeLoopLogStage::TimeLoopLogStage() { (void)PetscLogStagePush(time_loop_log_stage()); }

TimeLoopLogStage::~TimeLoopLogStage() { (void)PetscLogStagePop(); }

}  // namespace sph
