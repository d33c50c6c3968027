// The time-dependent node logic of clause 4.6.9 ("Time-dependent nodes") and 6.50
// (TimeSensor), written once for TimeSensor, MovieTexture and AudioClip: when a node
// becomes active, which cycle it is in, its fraction, and when it stops. Pure functions
// of the node's time fields and the current time; no events, no nodes.
#pragma once

#include <cstdint>

namespace gs::runtime {

/// The time fields of a time-dependent node, in seconds (SFTime, clause 4.11).
struct TimeFields {
  double startTime = 0.0;
  double stopTime = 0.0;
  /// TimeSensor.cycleInterval, or a media node's duration divided by |speed|. A node
  /// whose cycle is not positive never becomes active.
  double cycleInterval = 1.0;
  bool loop = false;
  bool enabled = true;  // TimeSensor.enabled; TRUE for media nodes
};

/// What a node remembers between evaluations.
struct TimeState {
  bool active = false;
  std::int64_t cycle = 0;  // index of the current cycle, counted from startTime
};

/// What one evaluation at time `now` gives.
struct TimeStep {
  bool activated = false;    // became active now: send isActive TRUE
  bool deactivated = false;  // became inactive now: send isActive FALSE
  bool newCycle = false;     // activated, or entered a new cycle: send cycleTime
  bool output = false;       // active now or just stopped: send fraction_changed and time
  double cycleTime = 0.0;    // start of the current cycle (seconds), when newCycle
  /// fraction_changed of 6.50: f = (t - startTime) / cycleInterval at t = min(now, the stop
  /// time), fraction = f - floor(f), and 1 when that is 0 with t > startTime; in [0, 1].
  double fraction = 0.0;
};

/// Evaluates the rules of 6.50 at `now` and updates `state`:
/// - an inactive node becomes active when enabled, now >= startTime, not
///   (stopTime > startTime and now >= stopTime), and (loop or now < startTime +
///   cycleInterval); a looping node with startTime 0 is then in cycle
///   floor(now / cycleInterval), its phase counted from 1970;
/// - an active node stops when disabled (no fraction), at stopTime when stopTime >
///   startTime, or at the end of its first cycle when not looping (fraction 1).
TimeStep evaluateTime(TimeState& state, const TimeFields& fields, double now);

/// Whether a write of startTime (or cycleInterval) to an active node is ignored (6.50:
/// "set_startTime events are ignored while the sensor is active"), and of stopTime when
/// stopTime <= startTime while active.
bool ignoresStopTime(const TimeState& state, const TimeFields& fields, double newStopTime);

}  // namespace gs::runtime
