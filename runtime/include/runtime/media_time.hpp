// The media time of MovieTexture (ISO/IEC 14772-1:1997 6.28) and AudioClip (6.3): the
// time-dependent rules of 4.6.9 (runtime/time_dependent.hpp) with a cycle of
// duration / |rate|, and where in the media an active (or stopped) node is. The runtime
// knows no decoder: the application tells it each clip's duration
// (ExecutionModel::setMediaDuration) and reads the media time back each frame
// (ExecutionModel::media) to pick a video frame or an audio position.
#pragma once

#include <optional>

namespace gs::runtime {

/// What the execution model knows of one MovieTexture or AudioClip.
struct MediaState {
  bool movie = false;  // MovieTexture (rate = speed); false: AudioClip (rate = pitch)
  /// Seconds of media, once the application reported it (setMediaDuration); empty until
  /// then, and -1 when the media could not be read.
  std::optional<double> duration;
  bool active = false;  // isActive (6.28, 6.3)
  /// Seconds into the media (0 .. duration) to show or play now: while active, by the
  /// rules of 6.28; while inactive, 0 before the first activation (duration for a
  /// MovieTexture with negative speed) and the position at which it stopped afterwards.
  double mediaTime = 0.0;
  /// The rate in use: MovieTexture.speed (negative plays backwards; 0 shows frame 0) or
  /// AudioClip.pitch (> 0), as it was when the node became active.
  double rate = 1.0;
};

/// Seconds into a clip of `duration` seconds at `fraction` (0..1, 6.50's fraction of a
/// cycle of duration / |rate|) played at `rate`: fraction * duration forwards, (1 -
/// fraction) * duration backwards (6.28: "t = duration - ((now - startTime) mod
/// |duration / speed|)").
inline double mediaTimeAt(double fraction, double duration, double rate) {
  return rate < 0.0 ? (1.0 - fraction) * duration : fraction * duration;
}

}  // namespace gs::runtime
