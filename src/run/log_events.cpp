#include "src/run/log_events.hpp"

#include <array>

namespace sph {

namespace {

struct Registered {
  std::array<PetscLogEvent, static_cast<int>(LogEvent::Count)> events{};
  PetscLogStage time_loop = 0;

  Registered() {
    static const char* const names[] = {"SPHStep",        "SPHNbrUpdate", "SPHNbrRebuild",  "SPHDensity",
                                        "SPHGasDensityH", "SPHGasPairs",  "SPHForces",      "SPHPPEAssembly",
                                        "SPHPPESolve",    "SPHShifting",  "SPHDiagnostics", "SPHOutput",
                                        "SPHCheckpoint"};
    static_assert(sizeof(names) / sizeof(names[0]) == static_cast<int>(LogEvent::Count), "one name per event");
    PetscClassId sph_class;
    PetscClassIdRegister("SPH", &sph_class);
    for (int k = 0; k < static_cast<int>(LogEvent::Count); ++k) PetscLogEventRegister(names[k], sph_class, &events[k]);
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

LogEventScope::LogEventScope(LogEvent e) : event_(log_event(e)) {
  (void)PetscLogEventBegin(event_, 0, 0, 0, 0);
}

void LogEventScope::end() {
  if (!open_) return;
  open_ = false;
  (void)PetscLogEventEnd(event_, 0, 0, 0, 0);
}

TimeLoopLogStage::TimeLoopLogStage() { (void)PetscLogStagePush(time_loop_log_stage()); }

TimeLoopLogStage::~TimeLoopLogStage() { (void)PetscLogStagePop(); }

}  // namespace sph
