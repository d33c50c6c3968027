// Clause 4.6.9 and 6.50 (TimeSensor): activation, cycles, fraction, stop.
#include "runtime/time_dependent.hpp"

#include <algorithm>
#include <cmath>

namespace gs::runtime {

namespace {

/// fraction_changed at time t of an active node (6.50).
double fractionAt(const TimeFields& f, double t) {
  const double x = (t - f.startTime) / f.cycleInterval;
  const double frac = x - std::floor(x);
  return (frac == 0.0 && t > f.startTime) ? 1.0 : frac;
}

std::int64_t cycleAt(const TimeFields& f, double t) {
  // Clamped: a tiny cycleInterval (a hostile file's 1e-30 s) makes more cycles than int64
  // holds, and converting such a double is undefined.
  const double c = std::floor((t - f.startTime) / f.cycleInterval);
  constexpr double kLimit = 9.0e18;
  return static_cast<std::int64_t>(std::clamp(std::isnan(c) ? 0.0 : c, -kLimit, kLimit));
}

bool stopsAt(const TimeFields& f, double t) {
  return f.stopTime > f.startTime && t >= f.stopTime;
}

}  // namespace

TimeStep evaluateTime(TimeState& state, const TimeFields& f, double now) {
  TimeStep step;
  const bool valid =
      f.cycleInterval > 0.0 && std::isfinite(f.cycleInterval) && std::isfinite(f.startTime);
  if (!state.active) {
    if (!valid || !f.enabled || now < f.startTime || stopsAt(f, now)) return step;
    if (!f.loop && now >= f.startTime + f.cycleInterval) return step;
    state.active = true;
    state.cycle = cycleAt(f, now);
    step.activated = step.newCycle = step.output = true;
    step.cycleTime = f.startTime + static_cast<double>(state.cycle) * f.cycleInterval;
    step.fraction = fractionAt(f, now);
    return step;
  }
  if (!valid || !f.enabled) {
    state.active = false;
    step.deactivated = true;
    return step;
  }
  if (stopsAt(f, now)) {
    state.active = false;
    step.deactivated = step.output = true;
    const double end = f.loop ? f.stopTime : std::min(f.stopTime, f.startTime + f.cycleInterval);
    step.fraction = fractionAt(f, end);
    return step;
  }
  if (!f.loop && now >= f.startTime + f.cycleInterval) {
    state.active = false;
    step.deactivated = step.output = true;
    step.fraction = 1.0;
    return step;
  }
  step.output = true;
  step.fraction = fractionAt(f, now);
  const std::int64_t cycle = cycleAt(f, now);
  if (cycle != state.cycle) {
    state.cycle = cycle;
    step.newCycle = true;
    step.cycleTime = f.startTime + static_cast<double>(cycle) * f.cycleInterval;
  }
  return step;
}

bool ignoresStopTime(const TimeState& state, const TimeFields& f, double newStopTime) {
  return state.active && newStopTime <= f.startTime;
}

}  // namespace gs::runtime
