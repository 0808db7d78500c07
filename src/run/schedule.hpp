#pragma once
// When a run stops, writes a frame and writes a checkpoint. t is a sum of steps, so t_end and the output
// and checkpoint times are reached up to round-off: every comparison of times goes through here, with one
// tolerance.
#include <cmath>
#include <limits>

namespace sph {

// Relative tolerance for comparing times.
constexpr double kTimeTolerance = 1e-12;

// t has reached `target`, up to round-off.
inline bool time_reached(double t, double target) { return t >= target * (1.0 - kTimeTolerance); }

// The step to take from t: `dt` shortened so that equal steps land on t_end. A last sliver of a step
// would be a different discretisation (ISPH's pressure scales with 1/dt).
inline double step_to_end(double t, double t_end, double dt) {
  const double remaining = t_end - t;
  return remaining / std::ceil(remaining / dt * (1.0 - kTimeTolerance));
}

// Events at every multiple of an interval (0: never), the first one after the start time t.
class Cadence {
 public:
  Cadence(double interval, double t)
      : interval_(interval),
        next_(interval > 0 ? interval * (std::floor(t / interval * (1.0 + kTimeTolerance)) + 1)
                           : std::numeric_limits<double>::infinity()) {}
  bool due(double t) const { return time_reached(t, next_); }
  double next() const { return next_; }  // infinity: never
  // Moves past t (a step longer than the interval skips the events it jumped over).
  void advance(double t) {
    while (next_ <= t * (1.0 + kTimeTolerance)) next_ += interval_;
  }

 private:
  double interval_, next_;
};

}  // namespace sph
