// The world's clock (ISO/IEC 14772-1:1997, clause 4.11 "Time"): SFTime values are seconds
// since 1970-01-01 00:00:00 UTC. Nothing in the execution model reads the system clock
// except wallClockSeconds(); everything else asks a Clock, so a test or a snapshot sets
// the time and gets the same events on any machine.
#pragma once

namespace gs::runtime {

/// Seconds since 1970-01-01 00:00:00 UTC from the system clock (microsecond resolution).
/// The one place the execution model reads wall time: the window calls it once a frame.
double wallClockSeconds();

/// A settable clock. Time never runs backwards: set() to an earlier time is ignored.
class Clock {
 public:
  /// A clock reading `start` seconds (SFTime; 0 is 1970-01-01).
  explicit Clock(double start = 0.0) : now_(start) {}
  /// The current SFTime in seconds.
  double now() const { return now_; }
  /// Moves to `t` seconds when t >= now(); returns whether the time changed.
  bool set(double t) {
    if (!(t > now_)) return false;
    now_ = t;
    return true;
  }
  /// Moves forward by `seconds` (ignored when not positive).
  void advance(double seconds) {
    if (seconds > 0.0) now_ += seconds;
  }

 private:
  double now_;
};

}  // namespace gs::runtime
